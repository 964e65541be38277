#include "viewer/swapchain.h"

#include <algorithm>
#include <cstring>

#include "gpu/context.h"
#include "gpu/vk_check.h"
#include "passes/frame/frames_in_flight.h"
#include "viewer/window.h"

namespace avsm::viewer {

namespace {

// UNORM first: the tonemapped image holds display-encoded values already.
VkSurfaceFormatKHR pick_format(VkPhysicalDevice device, VkSurfaceKHR surface) {
  uint32_t count = 0;
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(device, surface, &count, nullptr));
  std::vector<VkSurfaceFormatKHR> formats(count);
  VK_CHECK(vkGetPhysicalDeviceSurfaceFormatsKHR(device, surface, &count, formats.data()));
  if (formats.empty()) throw WindowError("the window surface offers no image formats");
  for (VkFormat wanted : {VK_FORMAT_B8G8R8A8_UNORM, VK_FORMAT_R8G8B8A8_UNORM})
    for (const VkSurfaceFormatKHR& f : formats)
      if (f.format == wanted) return f;
  throw WindowError("the window surface offers neither B8G8R8A8_UNORM nor R8G8B8A8_UNORM");
}

VkCompositeAlphaFlagBitsKHR pick_composite_alpha(VkCompositeAlphaFlagsKHR supported) {
  for (VkCompositeAlphaFlagBitsKHR bit : {VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR, VK_COMPOSITE_ALPHA_INHERIT_BIT_KHR,
                                          VK_COMPOSITE_ALPHA_PRE_MULTIPLIED_BIT_KHR,
                                          VK_COMPOSITE_ALPHA_POST_MULTIPLIED_BIT_KHR})
    if (supported & bit) return bit;
  return VK_COMPOSITE_ALPHA_OPAQUE_BIT_KHR;
}

VkSemaphore create_semaphore(VkDevice device) {
  VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO};
  VkSemaphore semaphore = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSemaphore(device, &info, nullptr, &semaphore));
  return semaphore;
}

}  // namespace

Swapchain::Swapchain(gpu::Context& ctx, VkSurfaceKHR surface, VkExtent2D wanted, uint32_t frames_in_flight)
    : ctx_(ctx), surface_(surface) {
  VkBool32 can_present = VK_FALSE;
  VK_CHECK(vkGetPhysicalDeviceSurfaceSupportKHR(ctx.physical_device(), ctx.graphics_queue().family, surface,
                                                &can_present));
  if (!can_present)
    throw WindowError("device '" + ctx.info().name + "' cannot present to the window from its graphics queue family " +
                      std::to_string(ctx.graphics_queue().family));
  passes::check_frames_in_flight(frames_in_flight);
  for (uint32_t i = 0; i < frames_in_flight; ++i) acquired_.push_back(create_semaphore(ctx.device()));
  create(wanted);
}

Swapchain::~Swapchain() {
  vkDeviceWaitIdle(ctx_.device());
  destroy_chain();
  vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
  for (VkSemaphore semaphore : acquired_) vkDestroySemaphore(ctx_.device(), semaphore, nullptr);
}

void Swapchain::recreate(VkExtent2D wanted) {
  vkDeviceWaitIdle(ctx_.device());
  destroy_chain();
  create(wanted);
}

void Swapchain::destroy_chain() {
  targets_.clear();
  for (VkImageView view : views_) vkDestroyImageView(ctx_.device(), view, nullptr);
  for (VkSemaphore semaphore : rendered_) vkDestroySemaphore(ctx_.device(), semaphore, nullptr);
  views_.clear();
  rendered_.clear();
  images_.clear();
}

void Swapchain::create(VkExtent2D wanted) {
  VkSurfaceCapabilitiesKHR caps{};
  VK_CHECK(vkGetPhysicalDeviceSurfaceCapabilitiesKHR(ctx_.physical_device(), surface_, &caps));
  extent_ = caps.currentExtent.width != UINT32_MAX
                ? caps.currentExtent
                : VkExtent2D{std::clamp(wanted.width, caps.minImageExtent.width, caps.maxImageExtent.width),
                             std::clamp(wanted.height, caps.minImageExtent.height, caps.maxImageExtent.height)};
  if (extent_.width == 0 || extent_.height == 0) return;  // minimised: nothing to draw into

  const VkImageUsageFlags needed = VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  if ((caps.supportedUsageFlags & needed) != needed)
    throw WindowError("the window surface does not allow transfer-destination colour-attachment images");
  readable_ = caps.supportedUsageFlags & VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  const VkSurfaceFormatKHR format = pick_format(ctx_.physical_device(), surface_);
  format_ = format.format;

  VkSwapchainCreateInfoKHR info{VK_STRUCTURE_TYPE_SWAPCHAIN_CREATE_INFO_KHR};
  info.surface = surface_;
  info.minImageCount = caps.maxImageCount ? std::min(caps.minImageCount + 1, caps.maxImageCount) : caps.minImageCount + 1;
  info.imageFormat = format.format;
  info.imageColorSpace = format.colorSpace;
  info.imageExtent = extent_;
  info.imageArrayLayers = 1;
  info.imageUsage = needed | (readable_ ? VK_IMAGE_USAGE_TRANSFER_SRC_BIT : 0);
  info.imageSharingMode = VK_SHARING_MODE_EXCLUSIVE;
  info.preTransform = caps.currentTransform;
  info.compositeAlpha = pick_composite_alpha(caps.supportedCompositeAlpha);
  info.presentMode = VK_PRESENT_MODE_FIFO_KHR;  // the one mode every surface has
  info.clipped = VK_TRUE;
  info.oldSwapchain = swapchain_;
  VkSwapchainKHR fresh = VK_NULL_HANDLE;
  VK_CHECK(vkCreateSwapchainKHR(ctx_.device(), &info, nullptr, &fresh));
  vkDestroySwapchainKHR(ctx_.device(), swapchain_, nullptr);
  swapchain_ = fresh;
  ctx_.set_name(swapchain_, VK_OBJECT_TYPE_SWAPCHAIN_KHR, "window swapchain");

  uint32_t count = 0;
  VK_CHECK(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &count, nullptr));
  images_.resize(count);
  VK_CHECK(vkGetSwapchainImagesKHR(ctx_.device(), swapchain_, &count, images_.data()));
  for (uint32_t i = 0; i < count; ++i) {
    VkImageViewCreateInfo view{VK_STRUCTURE_TYPE_IMAGE_VIEW_CREATE_INFO};
    view.image = images_[i];
    view.viewType = VK_IMAGE_VIEW_TYPE_2D;
    view.format = format_;
    view.subresourceRange = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
    VkImageView handle = VK_NULL_HANDLE;
    VK_CHECK(vkCreateImageView(ctx_.device(), &view, nullptr, &handle));
    views_.push_back(handle);
    rendered_.push_back(create_semaphore(ctx_.device()));
    ctx_.set_name(images_[i], VK_OBJECT_TYPE_IMAGE, "swapchain image " + std::to_string(i));
    gpu::ImageDesc desc;
    desc.width = extent_.width;
    desc.height = extent_.height;
    desc.format = format_;
    desc.name = "swapchain image " + std::to_string(i);
    targets_.push_back(gpu::Image::borrow(ctx_, images_[i], handle, desc));
  }
}

std::optional<uint32_t> Swapchain::acquire(uint32_t slot) {
  if (images_.empty()) return std::nullopt;
  uint32_t index = 0;
  const VkResult result =
      vkAcquireNextImageKHR(ctx_.device(), swapchain_, UINT64_MAX, acquired_.at(slot), VK_NULL_HANDLE, &index);
  if (result == VK_ERROR_OUT_OF_DATE_KHR) return std::nullopt;
  // SUBOPTIMAL still signals the semaphore: draw this frame, recreate after presenting.
  if (result != VK_SUBOPTIMAL_KHR) VK_CHECK(result);
  return index;
}

bool Swapchain::present(uint32_t image) {
  VkPresentInfoKHR info{VK_STRUCTURE_TYPE_PRESENT_INFO_KHR};
  info.waitSemaphoreCount = 1;
  info.pWaitSemaphores = &rendered_[image];
  info.swapchainCount = 1;
  info.pSwapchains = &swapchain_;
  info.pImageIndices = &image;
  const VkResult result = vkQueuePresentKHR(ctx_.graphics_queue().handle, &info);
  if (result == VK_ERROR_OUT_OF_DATE_KHR || result == VK_SUBOPTIMAL_KHR) return false;
  VK_CHECK(result);
  return true;
}

void Swapchain::record_readback(VkCommandBuffer cmd, uint32_t index, const gpu::Buffer& buffer) const {
  VkBufferImageCopy region{};
  region.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  region.imageExtent = {extent_.width, extent_.height, 1};
  vkCmdCopyImageToBuffer(cmd, images_[index], VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, buffer.handle(), 1, &region);
}

std::vector<uint8_t> Swapchain::to_rgba(const uint8_t* bytes) const {
  std::vector<uint8_t> rgba(bytes, bytes + size_t(extent_.width) * extent_.height * 4);
  if (format_ == VK_FORMAT_B8G8R8A8_UNORM)
    for (size_t i = 0; i < rgba.size(); i += 4) std::swap(rgba[i], rgba[i + 2]);
  return rgba;
}

}  // namespace avsm::viewer
