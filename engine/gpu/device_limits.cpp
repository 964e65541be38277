#include "gpu/device_limits.h"

#include <algorithm>
#include <cstdio>

#include "gpu/context.h"
#include "gpu/resources.h"
#include "gpu/vk_check.h"

namespace avsm::gpu {

std::string format_mib(uint64_t bytes) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f MiB", double(bytes) / double(1 << 20));
  return text;
}

static std::string setting_hint(const ResourceLabel& label) {
  return label.sized_by.empty() ? "" : "; lower " + label.sized_by;
}

void throw_over_limit(const ResourceLabel& label, const std::string& needed, const std::string& limit) {
  throw ResourceLimitError("'" + label.name + "' needs " + needed + ", over the device's " + limit +
                           setting_hint(label));
}

void check_buffer_limits(const Context& ctx, const BufferDesc& desc) {
  const DeviceInfo& info = ctx.info();
  const ResourceLabel label{desc.name, desc.sized_by};
  if (desc.size > info.max_buffer_size)
    throw_over_limit(label, format_mib(desc.size), "maxBufferSize of " + format_mib(info.max_buffer_size));
  // The engine binds a storage buffer whole: past the range no shader could read it.
  if ((desc.usage & VK_BUFFER_USAGE_STORAGE_BUFFER_BIT) && desc.size > info.max_storage_buffer_range)
    throw_over_limit(label, format_mib(desc.size),
                     "maxStorageBufferRange of " + format_mib(info.max_storage_buffer_range) +
                         " (the most a shader binding sees)");
}

void check_image_limits(const Context& ctx, const ImageDesc& desc) {
  const DeviceInfo& info = ctx.info();
  const ResourceLabel label{desc.name, desc.sized_by};
  const bool volume = image_type_of(desc) == VK_IMAGE_TYPE_3D;
  const uint32_t largest = std::max({desc.width, desc.height, volume ? desc.depth : 1u});
  const uint32_t limit = volume ? info.max_image_dimension_3d : info.max_image_dimension_2d;
  if (largest > limit) {
    // Appended, not prepended to a temporary: keeps g++ 12 free of a false -Wrestrict.
    std::string extent = std::to_string(desc.width) + "x" + std::to_string(desc.height);
    if (volume) extent.append("x").append(std::to_string(desc.depth));
    throw_over_limit(label, "a " + extent + " image",
                     std::string(volume ? "maxImageDimension3D" : "maxImageDimension2D") + " of " +
                         std::to_string(limit) + " texels");
  }
  if (desc.array_layers > info.max_image_array_layers)
    throw_over_limit(label, std::to_string(desc.array_layers) + " layers",
                     "maxImageArrayLayers of " + std::to_string(info.max_image_array_layers));
}

// What is left of a heap's budget (VK_EXT_memory_budget): the budget less what the
// process (and others, as the driver counts them) already uses.
static VkDeviceSize budget_left(const Context& ctx, uint32_t heap) {
  VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
  VkPhysicalDeviceMemoryProperties2 properties{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
  properties.pNext = &budget;
  vkGetPhysicalDeviceMemoryProperties2(ctx.physical_device(), &properties);
  const VkDeviceSize used = budget.heapUsage[heap];
  return budget.heapBudget[heap] > used ? budget.heapBudget[heap] - used : 0;
}

void check_memory_limits(const Context& ctx, VkDeviceSize bytes, uint32_t type, const ResourceLabel& label) {
  const DeviceInfo& info = ctx.info();
  if (bytes > info.max_memory_allocation_size)
    throw_over_limit(label, format_mib(bytes),
                     "maxMemoryAllocationSize of " + format_mib(info.max_memory_allocation_size));
  const uint32_t heap = ctx.memory_properties().memoryTypes[type].heapIndex;
  const VkDeviceSize heap_size = ctx.memory_properties().memoryHeaps[heap].size;
  if (bytes > heap_size)
    throw_over_limit(label, format_mib(bytes), "memory heap " + std::to_string(heap) + " of " + format_mib(heap_size));
  if (!info.memory_budget) return;
  const VkDeviceSize left = budget_left(ctx, heap);
  if (bytes > left)
    throw_over_limit(label, format_mib(bytes),
                     "memory budget: " + format_mib(left) + " left in heap " + std::to_string(heap));
}

void throw_allocation_failure(VkResult result, VkDeviceSize bytes, const ResourceLabel& label) {
  if (result == VK_ERROR_OUT_OF_DEVICE_MEMORY || result == VK_ERROR_OUT_OF_HOST_MEMORY)
    throw ResourceLimitError("'" + label.name + "' (" + format_mib(bytes) + ") did not fit: the device is out of " +
                             (result == VK_ERROR_OUT_OF_HOST_MEMORY ? "host" : "device") + " memory" +
                             setting_hint(label));
  throw VulkanError(result,
                    "creating '" + label.name + "' (" + format_mib(bytes) + ") failed with " + to_string(result));
}

}  // namespace avsm::gpu
