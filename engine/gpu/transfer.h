#pragma once
// Uploads and readbacks through host-visible staging buffers, each a one-shot
// submission that waits. For scene loading, tests and captured frames.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <cstring>
#include <span>
#include <string>
#include <vector>

#include "gpu/resources.h"

namespace avsm::gpu {

class Context;

// Creates a device-local buffer holding `bytes`.
Buffer create_buffer_with_data(const Context& ctx, BufferDesc desc, const void* data, VkDeviceSize bytes);
// A device-local buffer holding `data`; an empty vector gives one zeroed element,
// so shaders always have something valid to bind.
template <class T>
Buffer create_buffer_from(const Context& ctx, std::vector<T> data, VkBufferUsageFlags usage, const std::string& name) {
  if (data.empty()) data.push_back(T{});
  return create_buffer_with_data(ctx, {0, usage, MemoryLocation::DeviceLocal, name}, data.data(), data.size() * sizeof(T));
}

void upload_buffer(const Context& ctx, const Buffer& dst, const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);

std::vector<uint8_t> read_buffer_bytes(const Context& ctx, const Buffer& src);
template <class T>
std::vector<T> read_buffer(const Context& ctx, const Buffer& src) {
  std::vector<uint8_t> bytes = read_buffer_bytes(ctx, src);
  std::vector<T> out(bytes.size() / sizeof(T));
  std::memcpy(out.data(), bytes.data(), out.size() * sizeof(T));
  return out;
}

// A readback of one mip level / layer as RGBA float, whatever the format.
struct ImageRGBA32F {
  uint32_t width = 0, height = 0;
  std::vector<float> pixels;  // width * height * 4
  float* at(uint32_t x, uint32_t y) { return &pixels[(size_t(y) * width + x) * 4]; }
  const float* at(uint32_t x, uint32_t y) const { return &pixels[(size_t(y) * width + x) * 4]; }
};

// The image must have TRANSFER_SRC usage and be in `layout`; it is returned to
// `layout` afterwards (TRANSFER_SRC_OPTIMAL if it was UNDEFINED).
ImageRGBA32F read_image(const Context& ctx, const Image& image, VkImageLayout layout, uint32_t mip = 0,
                        uint32_t layer = 0);

// Records a copy of `image` (mip 0, layer 0, in `layout` with TRANSFER_SRC usage) into the
// host-readable `buffer`, visible to the host once the command buffer completed: a frame's
// own readback, for a frame slot's buffer.
void record_image_readback(VkCommandBuffer cmd, const Image& image, VkImageLayout layout, const Buffer& buffer);

// Fills mip 0 / layer 0 from tightly packed texels and leaves it in `final_layout`
// (visible to all later shader reads).
void upload_image(const Context& ctx, const Image& image, const void* texels, VkDeviceSize bytes,
                  VkImageLayout final_layout);
// The same for every mip level: levels[i] holds level i's tightly packed texels (one per
// level of the image, layer 0).
void upload_image_levels(const Context& ctx, const Image& image, const std::vector<std::span<const std::uint8_t>>& levels,
                         VkImageLayout final_layout);

}  // namespace avsm::gpu
