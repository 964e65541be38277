#include "gpu/transfer.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <stdexcept>

#include "gpu/barriers.h"
#include "gpu/context.h"

namespace avsm::gpu {

// Conservative: whatever touched the resource before this one-shot submission.
static constexpr Access kAnyPriorWork{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT,
                                      VK_ACCESS_2_MEMORY_READ_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT};

static Buffer staging(const Context& ctx, VkDeviceSize bytes, MemoryLocation location) {
  return Buffer::create(ctx, {bytes, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT, location,
                              location == MemoryLocation::HostUpload ? "staging upload" : "staging readback"});
}

void upload_buffer(const Context& ctx, const Buffer& dst, const void* data, VkDeviceSize bytes, VkDeviceSize offset) {
  if (offset + bytes > dst.size()) throw std::runtime_error("upload overflows buffer '" + dst.name() + "'");
  Buffer stage = staging(ctx, bytes, MemoryLocation::HostUpload);
  stage.upload(data, bytes);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    buffer_barrier(cmd, dst.handle(), kAnyPriorWork, kTransferWrite);
    VkBufferCopy region{0, dst.offset() + offset, bytes};
    vkCmdCopyBuffer(cmd, stage.handle(), dst.handle(), 1, &region);
    buffer_barrier(cmd, dst.handle(), kTransferWrite, kAnyPriorWork);
  });
}

Buffer create_buffer_with_data(const Context& ctx, BufferDesc desc, const void* data, VkDeviceSize bytes) {
  desc.usage |= VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  if (desc.size == 0) desc.size = bytes;
  Buffer buffer = Buffer::create(ctx, desc);
  upload_buffer(ctx, buffer, data, bytes);
  return buffer;
}

std::vector<uint8_t> read_buffer_bytes(const Context& ctx, const Buffer& src) {
  Buffer stage = staging(ctx, src.size(), MemoryLocation::HostReadback);
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    buffer_barrier(cmd, src.handle(), kAnyPriorWork, kTransferRead);
    VkBufferCopy region{src.offset(), 0, src.size()};
    vkCmdCopyBuffer(cmd, src.handle(), stage.handle(), 1, &region);
    buffer_barrier(cmd, stage.handle(), kTransferWrite, kHostRead);
  });
  const auto* bytes = static_cast<const uint8_t*>(stage.mapped());
  return {bytes, bytes + src.size()};
}

static float half_to_float(uint16_t h) {
  uint32_t sign = (h >> 15) & 1, exponent = (h >> 10) & 0x1f, mantissa = h & 0x3ff;
  float value;
  if (exponent == 0) value = std::ldexp(float(mantissa), -24);
  else if (exponent == 31) value = mantissa ? NAN : INFINITY;
  else value = std::ldexp(float(mantissa | 0x400), int(exponent) - 25);
  return sign ? -value : value;
}

// Converts one texel to RGBA float; missing channels read as (0, 0, 0, 1).
static void decode_texel(VkFormat format, const uint8_t* texel, float* rgba) {
  rgba[0] = rgba[1] = rgba[2] = 0.0f;
  rgba[3] = 1.0f;
  switch (format) {
    case VK_FORMAT_R8G8B8A8_UNORM:
    case VK_FORMAT_R8G8B8A8_SRGB:
      for (int c = 0; c < 4; ++c) rgba[c] = texel[c] / 255.0f;
      return;
    case VK_FORMAT_B8G8R8A8_UNORM:
    case VK_FORMAT_B8G8R8A8_SRGB:
      rgba[0] = texel[2] / 255.0f, rgba[1] = texel[1] / 255.0f, rgba[2] = texel[0] / 255.0f, rgba[3] = texel[3] / 255.0f;
      return;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
      for (int c = 0; c < 4; ++c) rgba[c] = half_to_float(reinterpret_cast<const uint16_t*>(texel)[c]);
      return;
    case VK_FORMAT_R16G16_SFLOAT:
      for (int c = 0; c < 2; ++c) rgba[c] = half_to_float(reinterpret_cast<const uint16_t*>(texel)[c]);
      return;
    case VK_FORMAT_R16_SFLOAT: rgba[0] = half_to_float(*reinterpret_cast<const uint16_t*>(texel)); return;
    case VK_FORMAT_R32G32B32A32_SFLOAT: std::memcpy(rgba, texel, 16); return;
    case VK_FORMAT_R32G32_SFLOAT: std::memcpy(rgba, texel, 8); return;
    case VK_FORMAT_R32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT: std::memcpy(rgba, texel, 4); return;
    case VK_FORMAT_R32_UINT: rgba[0] = float(*reinterpret_cast<const uint32_t*>(texel)); return;
    case VK_FORMAT_R8_UNORM: rgba[0] = texel[0] / 255.0f; return;
    default: throw std::runtime_error("read_image: unsupported format " + std::to_string(int(format)));
  }
}

void record_image_readback(VkCommandBuffer cmd, const Image& image, VkImageLayout layout, const Buffer& buffer) {
  VkBufferImageCopy copy{};
  copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
  copy.imageExtent = {image.desc().width, image.desc().height, 1};
  vkCmdCopyImageToBuffer(cmd, image.handle(), layout, buffer.handle(), 1, &copy);
  buffer_barrier(cmd, buffer.handle(), kTransferWrite, kHostRead);
}

ImageRGBA32F read_image(const Context& ctx, const Image& image, VkImageLayout layout, uint32_t mip, uint32_t layer) {
  const ImageDesc& desc = image.desc();
  uint32_t width = std::max(1u, desc.width >> mip), height = std::max(1u, desc.height >> mip);
  uint32_t texel_bytes = format_bytes_per_texel(desc.format);
  Buffer stage = staging(ctx, VkDeviceSize(width) * height * texel_bytes, MemoryLocation::HostReadback);
  VkImageSubresourceRange range = image.full_range();
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    image_barrier(cmd, image.handle(), range, layout, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, kAnyPriorWork, kTransferRead);
    VkBufferImageCopy region{};
    region.imageSubresource = {image.aspect(), mip, layer, 1};
    region.imageExtent = {width, height, 1};
    vkCmdCopyImageToBuffer(cmd, image.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, stage.handle(), 1, &region);
    VkImageLayout back = layout == VK_IMAGE_LAYOUT_UNDEFINED ? VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL : layout;
    image_barrier(cmd, image.handle(), range, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, back, kTransferRead, kAnyPriorWork);
    buffer_barrier(cmd, stage.handle(), kTransferWrite, kHostRead);
  });
  ImageRGBA32F out{width, height, std::vector<float>(size_t(width) * height * 4)};
  const auto* texels = static_cast<const uint8_t*>(stage.mapped());
  for (size_t i = 0; i < size_t(width) * height; ++i) decode_texel(desc.format, texels + i * texel_bytes, &out.pixels[i * 4]);
  return out;
}

void upload_image(const Context& ctx, const Image& image, const void* texels, VkDeviceSize bytes, VkImageLayout final_layout) {
  upload_image_levels(ctx, image, {std::span(static_cast<const std::uint8_t*>(texels), bytes)}, final_layout);
}

void upload_image_levels(const Context& ctx, const Image& image, const std::vector<std::span<const std::uint8_t>>& levels,
                         VkImageLayout final_layout) {
  VkDeviceSize total = 0;
  for (const auto& level : levels) total += level.size();
  Buffer stage = staging(ctx, total, MemoryLocation::HostUpload);
  std::vector<VkBufferImageCopy> regions;
  VkDeviceSize offset = 0;
  const ImageDesc& desc = image.desc();
  for (uint32_t mip = 0; mip < levels.size(); ++mip) {
    stage.upload(levels[mip].data(), levels[mip].size(), offset);
    VkBufferImageCopy region{};
    region.bufferOffset = offset;
    region.imageSubresource = {image.aspect(), mip, 0, 1};
    region.imageExtent = {std::max(1u, desc.width >> mip), std::max(1u, desc.height >> mip), std::max(1u, desc.depth >> mip)};
    regions.push_back(region);
    offset += levels[mip].size();
  }
  VkImageSubresourceRange range = image.full_range();
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    image_barrier(cmd, image.handle(), range, VK_IMAGE_LAYOUT_UNDEFINED, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                  kAnyPriorWork, kTransferWrite);
    vkCmdCopyBufferToImage(cmd, stage.handle(), image.handle(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                           uint32_t(regions.size()), regions.data());
    image_barrier(cmd, image.handle(), range, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, final_layout, kTransferWrite,
                  kAnyPriorWork);
  });
}

}  // namespace avsm::gpu
