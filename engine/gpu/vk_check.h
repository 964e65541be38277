#pragma once
// Error handling for Vulkan calls: every failing call becomes an exception that
// names the call, the result and the source line, so tools can print it and exit.
#include <vulkan/vulkan.h>

#include <stdexcept>
#include <string>

namespace avsm::gpu {

class VulkanError : public std::runtime_error {
 public:
  VulkanError(VkResult result, const std::string& what) : std::runtime_error(what), result_(result) {}
  VkResult result() const { return result_; }

 private:
  VkResult result_;
};

const char* to_string(VkResult result);
[[noreturn]] void throw_vulkan_error(VkResult result, const char* call, const char* file, int line);

}  // namespace avsm::gpu

#define VK_CHECK(call)                                                           \
  do {                                                                           \
    VkResult vk_check_result_ = (call);                                          \
    if (vk_check_result_ < 0)                                                    \
      ::avsm::gpu::throw_vulkan_error(vk_check_result_, #call, __FILE__, __LINE__); \
  } while (0)
