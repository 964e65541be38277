#pragma once
// Buffers, images, samplers and the memory they live in.
//
// Two ways to back a resource with memory:
//  - create(): its own allocation (persistent resources: scene data, maps kept
//    across frames, readback buffers);
//  - create_placed(): at a chosen offset inside a shared MemoryHeap (transient
//    resources of the frame graph, which aliases several of them in one heap).
// memory_requirements() gives the driver's real size/alignment for a description
// without creating anything, so the graph can plan placements before allocating.
// Each of these checks the description against the device's limits first
// (gpu/device_limits.h) and throws ResourceLimitError for what the device cannot hold.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <span>
#include <optional>
#include <string>
#include <utility>
#include <vector>

namespace avsm::gpu {

class Context;

enum class MemoryLocation {
  DeviceLocal,   // GPU-only
  HostUpload,    // CPU writes, GPU reads (mapped)
  HostReadback,  // GPU writes, CPU reads (mapped, cached when possible)
};

struct MemoryRequirements {
  VkDeviceSize size = 0;
  VkDeviceSize alignment = 1;
  uint32_t memory_type_bits = 0;
};

// One VkDeviceMemory block that placed resources are bound into.
class MemoryHeap {
 public:
  MemoryHeap() = default;
  // `sized_by`: what decides its size, said when it does not fit the device.
  MemoryHeap(const Context& ctx, VkDeviceSize size, uint32_t memory_type_bits, MemoryLocation location,
             const std::string& name, const std::string& sized_by = {});
  ~MemoryHeap();
  MemoryHeap(MemoryHeap&& other) noexcept;
  MemoryHeap& operator=(MemoryHeap&& other) noexcept;

  VkDeviceMemory handle() const { return memory_; }
  VkDeviceSize size() const { return size_; }
  uint32_t memory_type() const { return memory_type_; }
  void* mapped() const { return mapped_; }

 private:
  void release();
  const Context* ctx_ = nullptr;
  VkDeviceMemory memory_ = VK_NULL_HANDLE;
  VkDeviceSize size_ = 0;
  uint32_t memory_type_ = 0;
  void* mapped_ = nullptr;
};

class Buffer;

// The part of a buffer a descriptor or a command sees: the whole buffer unless a
// range is given. Converts to VkBuffer, for commands that take the handle. A bare
// VkBuffer (a host's buffer) is its whole range, of a size the engine does not know.
struct BufferRange {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize size = VK_WHOLE_SIZE;  // bytes from offset; VK_WHOLE_SIZE: the rest, size unknown
  VkDeviceSize offset = 0;
  BufferRange() = default;
  BufferRange(VkBuffer buffer) : buffer(buffer) {}  // NOLINT(google-explicit-constructor)
  BufferRange(VkBuffer buffer, VkDeviceSize size, VkDeviceSize offset = 0) : buffer(buffer), size(size), offset(offset) {}
  BufferRange(const Buffer& whole);  // NOLINT(google-explicit-constructor): a buffer is its whole range
  operator VkBuffer() const { return buffer; }  // NOLINT(google-explicit-constructor)
};

struct BufferDesc {
  VkDeviceSize size = 0;
  VkBufferUsageFlags usage = 0;
  MemoryLocation location = MemoryLocation::DeviceLocal;
  std::string name;
  // The setting that sizes it, said when it does not fit the device (gpu/device_limits.h):
  // "the light's shadow.resolution (--shadow-res)". Empty: nothing the user sets.
  std::string sized_by;
};

class Buffer {
 public:
  Buffer() = default;
  static Buffer create(const Context& ctx, const BufferDesc& desc);
  static Buffer create_placed(const Context& ctx, const BufferDesc& desc, const MemoryHeap& heap,
                              VkDeviceSize offset);
  // Bytes [offset, offset + size) of `parent`, as a buffer of its own: descriptors,
  // barriers and transfers made from it see that range only. It owns nothing; `parent`
  // must outlive it. (Several shadow maps live in one atlas buffer this way.)
  static Buffer region(const Buffer& parent, VkDeviceSize offset, VkDeviceSize size, std::string name);
  ~Buffer();
  Buffer(Buffer&& other) noexcept;
  Buffer& operator=(Buffer&& other) noexcept;

  VkBuffer handle() const { return buffer_; }
  VkDeviceSize size() const { return size_; }
  // Where this buffer starts in handle(): 0 but for a region().
  VkDeviceSize offset() const { return offset_; }
  const std::string& name() const { return name_; }
  explicit operator bool() const { return buffer_ != VK_NULL_HANDLE; }

  // Host-visible buffers only. Coherent memory is requested, so no flushes are needed.
  void* mapped() const { return mapped_; }
  template <class T>
  std::span<T> view() const {
    return {static_cast<T*>(mapped_), size_t(size_ / sizeof(T))};
  }
  void upload(const void* data, VkDeviceSize bytes, VkDeviceSize offset = 0);

 private:
  void release();
  const Context* ctx_ = nullptr;
  VkBuffer buffer_ = VK_NULL_HANDLE;
  VkDeviceMemory own_memory_ = VK_NULL_HANDLE;  // null when placed in a heap
  VkDeviceSize size_ = 0;
  VkDeviceSize offset_ = 0;
  bool owns_handle_ = true;  // false for a region
  void* mapped_ = nullptr;
  std::string name_;
};

struct ImageDesc {
  uint32_t width = 1, height = 1, depth = 1;
  uint32_t mip_levels = 1, array_layers = 1;
  bool volume = false;  // a 3D image (and view) even when depth is 1
  VkFormat format = VK_FORMAT_R8G8B8A8_UNORM;
  VkImageUsageFlags usage = 0;
  std::string name;
  std::string sized_by;  // as BufferDesc::sized_by
};

class Image {
 public:
  Image() = default;
  static Image create(const Context& ctx, const ImageDesc& desc);
  static Image create_placed(const Context& ctx, const ImageDesc& desc, const MemoryHeap& heap,
                             VkDeviceSize offset);
  // An image and view owned elsewhere (a swapchain's), so that it can be bound like any
  // other; destroying the Image destroys only the mip views it created.
  static Image borrow(const Context& ctx, VkImage image, VkImageView view, const ImageDesc& desc);
  ~Image();
  Image(Image&& other) noexcept;
  Image& operator=(Image&& other) noexcept;

  VkImage handle() const { return image_; }
  VkImageView view() const { return view_; }  // all mips and layers
  // A view of one mip level (all layers), created on first use.
  VkImageView mip_view(uint32_t level) const;
  const ImageDesc& desc() const { return desc_; }
  VkImageAspectFlags aspect() const;
  VkImageSubresourceRange full_range() const;
  explicit operator bool() const { return image_ != VK_NULL_HANDLE; }

 private:
  void create_image(const Context& ctx, const ImageDesc& desc);
  void create_view();
  void release();
  const Context* ctx_ = nullptr;
  VkImage image_ = VK_NULL_HANDLE;
  VkImageView view_ = VK_NULL_HANDLE;
  mutable std::vector<VkImageView> mip_views_;  // a cache: filled by the const mip_view()
  VkDeviceMemory own_memory_ = VK_NULL_HANDLE;
  bool borrowed_ = false;  // image_ and view_ belong to someone else
  ImageDesc desc_;
};

struct SamplerDesc {
  VkFilter filter = VK_FILTER_LINEAR;
  VkSamplerMipmapMode mip_mode = VK_SAMPLER_MIPMAP_MODE_LINEAR;
  VkSamplerAddressMode address = VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE;
  bool compare = false;  // depth comparison (hardware PCF)
  VkCompareOp compare_op = VK_COMPARE_OP_LESS_OR_EQUAL;
  VkBorderColor border = VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE;
  std::string name;
  // Where minification or V differ from the above (glTF samplers set each on its own).
  std::optional<VkFilter> min_filter;
  std::optional<VkSamplerAddressMode> address_v;
  float max_lod = VK_LOD_CLAMP_NONE;  // 0.25 with MIPMAP_MODE_NEAREST: level 0 only (the spec's way)
};

// A sampler that reads texels as they are (nearest, no mips, clamped): a depth buffer
// read by texelFetch, for a pass whose shader declares a sampler2D.
inline SamplerDesc texel_sampler_desc(std::string name) {
  return {VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false,
          VK_COMPARE_OP_LESS_OR_EQUAL, VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE, std::move(name)};
}

class Sampler {
 public:
  Sampler() = default;
  Sampler(const Context& ctx, const SamplerDesc& desc);
  ~Sampler();
  Sampler(Sampler&& other) noexcept;
  Sampler& operator=(Sampler&& other) noexcept;
  VkSampler handle() const { return sampler_; }

 private:
  const Context* ctx_ = nullptr;
  VkSampler sampler_ = VK_NULL_HANDLE;
};

// The driver's real requirements for a resource, without creating it.
MemoryRequirements memory_requirements(const Context& ctx, const BufferDesc& desc);
MemoryRequirements memory_requirements(const Context& ctx, const ImageDesc& desc);

bool is_depth_format(VkFormat format);
uint32_t format_bytes_per_texel(VkFormat format);
VkImageType image_type_of(const ImageDesc& desc);

}  // namespace avsm::gpu
