#pragma once
// The device's limits, checked before a resource is made: every buffer, image and
// memory heap goes through these checks (memory_requirements(), Buffer/Image::create*,
// MemoryHeap), so nothing asks Vulkan for what it cannot give. Over a limit throws
// ResourceLimitError: one line naming the resource, what it needs, the limit and the
// setting that sizes it (BufferDesc/ImageDesc::sized_by), never a Vulkan code.
//
// The limits: maxBufferSize, maxStorageBufferRange (a storage buffer is bound whole, so
// no shader could see past it), maxImageDimension2D/3D, maxImageArrayLayers,
// maxMemoryAllocationSize, the size of the memory heap it lands in and, with
// VK_EXT_memory_budget, what is left of that heap's budget.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <stdexcept>
#include <string>

namespace avsm::gpu {

class Context;
struct BufferDesc;
struct ImageDesc;

class ResourceLimitError : public std::runtime_error {
 public:
  using std::runtime_error::runtime_error;
};

// "1.50 MiB": how byte counts read in messages.
std::string format_mib(uint64_t bytes);

// What one resource is, for messages: its name, and the setting that sizes it.
struct ResourceLabel {
  std::string name;
  std::string sized_by;  // "the light's shadow.resolution (--shadow-res)"; empty: none to name
};

// Throws ResourceLimitError saying that `label` needs `needed`, over the device's `limit`.
[[noreturn]] void throw_over_limit(const ResourceLabel& label, const std::string& needed, const std::string& limit);

// Before the handle is made (or its requirements asked for): sizes and dimensions.
void check_buffer_limits(const Context& ctx, const BufferDesc& desc);
void check_image_limits(const Context& ctx, const ImageDesc& desc);
// Before memory is allocated (or planned) for `label`: `bytes` of memory type `type`.
void check_memory_limits(const Context& ctx, VkDeviceSize bytes, uint32_t type, const ResourceLabel& label);

// An allocation that failed for lack of memory, which no limit foretold: names the
// resource and its bytes. Other results are thrown as VulkanError.
[[noreturn]] void throw_allocation_failure(VkResult result, VkDeviceSize bytes, const ResourceLabel& label);

}  // namespace avsm::gpu
