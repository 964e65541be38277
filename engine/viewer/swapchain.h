#pragma once
// The window's swapchain and the semaphores around it: acquire an image (signalling
// the frame slot's semaphore), record into it, submit (renderer/frame_slots.h: waiting
// for the acquire, signalling the image's rendered semaphore) and present. With frames
// in flight each slot has its own acquire semaphore, free again once the slot's fence
// signalled (the submit that waited on it completed). Images are B8G8R8A8/R8G8B8A8
// UNORM, so the renderer's tonemapped values (already display-encoded) are copied
// through unchanged, and carry TRANSFER_DST (the blit), COLOR_ATTACHMENT (the panel)
// and, where the surface allows, TRANSFER_SRC (window screenshots).
#include <vulkan/vulkan.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "gpu/resources.h"

namespace avsm::gpu {
class Context;
}

namespace avsm::viewer {

class Swapchain {
 public:
  // Throws WindowError when the device's queue cannot present to `surface` or the
  // surface lacks what the viewer needs.
  // `frames_in_flight`: the frame slots that acquire images (1..passes::kMaxFramesInFlight).
  Swapchain(gpu::Context& ctx, VkSurfaceKHR surface, VkExtent2D wanted, uint32_t frames_in_flight);
  ~Swapchain();
  Swapchain(const Swapchain&) = delete;
  Swapchain& operator=(const Swapchain&) = delete;

  // A new chain for a new window size (waits for the device to idle).
  void recreate(VkExtent2D wanted);

  // The image to draw this frame into, in UNDEFINED layout, for frame slot `slot`
  // (whose previous frame completed); acquired(slot) signals when it may be written.
  // nullopt when the chain is out of date (recreate it and try again).
  std::optional<uint32_t> acquire(uint32_t slot);
  VkSemaphore acquired(uint32_t slot) const { return acquired_.at(slot); }
  // What the frame drawing into `image` signals, and its present waits for.
  VkSemaphore rendered(uint32_t image) const { return rendered_.at(image); }
  // Where the submit waits for the acquired image: the first use of the image must wait
  // for these stages (they equal the sync1 TRANSFER | COLOR_ATTACHMENT_OUTPUT bits).
  static constexpr VkPipelineStageFlags2 kAcquireWaitStages =
      VK_PIPELINE_STAGE_2_ALL_TRANSFER_BIT | VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;

  // Presents `image` once rendered(image) signals (its frame left it in PRESENT_SRC_KHR).
  // Returns false when the chain should be recreated.
  bool present(uint32_t image);

  // Image `index` as a (borrowed) gpu::Image, for binding into a frame graph.
  const gpu::Image& target(uint32_t index) const { return targets_[index]; }
  VkFormat format() const { return format_; }
  VkExtent2D extent() const { return extent_; }
  bool can_read_back() const { return readable_; }

  // Records a copy of swapchain image `index` (in TRANSFER_SRC_OPTIMAL) into
  // `buffer` (host-readable, extent.width * extent.height * 4 bytes).
  void record_readback(VkCommandBuffer cmd, uint32_t index, const gpu::Buffer& buffer) const;
  // The copied bytes as RGBA8 rows, top to bottom, whatever the chain's channel order.
  std::vector<uint8_t> to_rgba(const uint8_t* bytes) const;

 private:
  void create(VkExtent2D wanted);
  void destroy_chain();

  gpu::Context& ctx_;
  VkSurfaceKHR surface_;
  VkSwapchainKHR swapchain_ = VK_NULL_HANDLE;
  VkFormat format_ = VK_FORMAT_UNDEFINED;
  VkExtent2D extent_{};
  bool readable_ = false;
  std::vector<VkImage> images_;
  std::vector<VkImageView> views_;
  std::vector<gpu::Image> targets_;  // images_ and views_, borrowed
  // One per image: a semaphore may only be signalled again once its present is done,
  // which is known when that image is acquired again.
  std::vector<VkSemaphore> rendered_;
  std::vector<VkSemaphore> acquired_;  // one per frame slot
};

}  // namespace avsm::viewer
