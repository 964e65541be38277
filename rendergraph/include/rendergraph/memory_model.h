#pragma once
// What the memory planner needs to know about the device. The Vulkan backend implements
// this with vkGetDeviceImageMemoryRequirements / vkGetDeviceBufferMemoryRequirements and
// VkPhysicalDeviceLimits::bufferImageGranularity; tests use a mock. Queries are const:
// the answers must not depend on the order they are asked in.
#include <rendergraph/usage.h>

#include <string>

namespace rg {

struct MemoryRequirements {
  uint64_t size = 0;
  uint64_t alignment = 1;
  uint32_t memory_type_bits = 0;

  bool operator==(const MemoryRequirements&) const = default;
};

class MemoryModel {
 public:
  virtual ~MemoryModel() = default;
  // `usages` is every usage the resource sees in the plan (see image_usage_flags()); `name`
  // is the resource's, for a model that refuses what the device cannot hold (and says so).
  virtual MemoryRequirements texture(const TextureDesc& desc, UsageSet usages, const std::string& name) const = 0;
  virtual MemoryRequirements buffer(const BufferDesc& desc, UsageSet usages, const std::string& name) const = 0;
  virtual uint64_t buffer_image_granularity() const = 0;
};

}  // namespace rg
