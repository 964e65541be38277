#include "gpu/vk_check.h"

#include <sstream>

namespace avsm::gpu {

const char* to_string(VkResult result) {
  switch (result) {
#define AVSM_CASE(r) \
  case r:            \
    return #r;
    AVSM_CASE(VK_SUCCESS)
    AVSM_CASE(VK_NOT_READY)
    AVSM_CASE(VK_TIMEOUT)
    AVSM_CASE(VK_INCOMPLETE)
    AVSM_CASE(VK_ERROR_OUT_OF_HOST_MEMORY)
    AVSM_CASE(VK_ERROR_OUT_OF_DEVICE_MEMORY)
    AVSM_CASE(VK_ERROR_INITIALIZATION_FAILED)
    AVSM_CASE(VK_ERROR_DEVICE_LOST)
    AVSM_CASE(VK_ERROR_MEMORY_MAP_FAILED)
    AVSM_CASE(VK_ERROR_LAYER_NOT_PRESENT)
    AVSM_CASE(VK_ERROR_EXTENSION_NOT_PRESENT)
    AVSM_CASE(VK_ERROR_FEATURE_NOT_PRESENT)
    AVSM_CASE(VK_ERROR_INCOMPATIBLE_DRIVER)
    AVSM_CASE(VK_ERROR_TOO_MANY_OBJECTS)
    AVSM_CASE(VK_ERROR_FORMAT_NOT_SUPPORTED)
    AVSM_CASE(VK_ERROR_FRAGMENTED_POOL)
    AVSM_CASE(VK_ERROR_OUT_OF_POOL_MEMORY)
    AVSM_CASE(VK_ERROR_SURFACE_LOST_KHR)
    AVSM_CASE(VK_ERROR_OUT_OF_DATE_KHR)
    AVSM_CASE(VK_SUBOPTIMAL_KHR)
#undef AVSM_CASE
    default:
      return "VK_RESULT_UNKNOWN";
  }
}

void throw_vulkan_error(VkResult result, const char* call, const char* file, int line) {
  std::ostringstream message;
  message << call << " failed with " << to_string(result) << " (" << static_cast<int>(result) << ") at "
          << file << ":" << line;
  throw VulkanError(result, message.str());
}

}  // namespace avsm::gpu
