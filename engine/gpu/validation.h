#pragma once
// Collects the messages of VK_LAYER_KHRONOS_validation (synchronization
// validation included) so tests can fail on any of them and tools can print them.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <mutex>
#include <string>
#include <vector>

namespace avsm::gpu {

struct ValidationMessage {
  VkDebugUtilsMessageSeverityFlagBitsEXT severity;
  std::string id_name;  // e.g. "SYNC-HAZARD-READ-AFTER-WRITE", "VUID-vkCmdDraw-None-02699"
  std::string text;
  bool is_sync_hazard() const { return id_name.rfind("SYNC-", 0) == 0; }
};

// Messages that are known to be harmless and are dropped, each with the reason.
// Keep this list short: anything added here is invisible to every test.
struct IgnoredMessage {
  const char* id_name;
  const char* reason;
};
const std::vector<IgnoredMessage>& ignored_validation_messages();

class ValidationLog {
 public:
  // Called from the layer's callback (any thread).
  void record(VkDebugUtilsMessageSeverityFlagBitsEXT severity, const char* id_name, const char* text);

  // Returns everything recorded since the last call and forgets it.
  std::vector<ValidationMessage> take();
  size_t count() const;

  // Echo each message to stderr as it arrives (tools do; tests print on failure).
  void set_echo(bool echo) { echo_ = echo; }

 private:
  mutable std::mutex mutex_;
  std::vector<ValidationMessage> messages_;
  bool echo_ = false;
};

// Human-readable summary of messages, for test failures and tool errors.
std::string describe(const std::vector<ValidationMessage>& messages);

VKAPI_ATTR VkBool32 VKAPI_CALL validation_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT types,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user_data);

}  // namespace avsm::gpu
