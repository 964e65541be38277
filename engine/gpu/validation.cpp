#include "gpu/validation.h"

#include <cstdio>
#include <cstring>
#include <sstream>

namespace avsm::gpu {

const std::vector<IgnoredMessage>& ignored_validation_messages() {
  static const std::vector<IgnoredMessage> list = {
      // The loader reports every ICD/layer JSON it could not use (e.g. Intel and
      // Radeon drivers installed by mesa-vulkan-drivers on a CPU-only machine).
      {"Loader Message", "driver discovery chatter from the Vulkan loader, not about our API use"},
  };
  return list;
}

static bool is_ignored(const char* id_name) {
  if (id_name == nullptr) return false;
  for (const IgnoredMessage& ignored : ignored_validation_messages())
    if (std::strcmp(ignored.id_name, id_name) == 0) return true;
  return false;
}

void ValidationLog::record(VkDebugUtilsMessageSeverityFlagBitsEXT severity, const char* id_name,
                           const char* text) {
  if (is_ignored(id_name)) return;
  ValidationMessage message{severity, id_name ? id_name : "", text ? text : ""};
  std::lock_guard lock(mutex_);
  if (echo_) std::fprintf(stderr, "[vulkan] %s: %s\n", message.id_name.c_str(), message.text.c_str());
  messages_.push_back(std::move(message));
}

std::vector<ValidationMessage> ValidationLog::take() {
  std::lock_guard lock(mutex_);
  std::vector<ValidationMessage> out;
  out.swap(messages_);
  return out;
}

size_t ValidationLog::count() const {
  std::lock_guard lock(mutex_);
  return messages_.size();
}

std::string describe(const std::vector<ValidationMessage>& messages) {
  std::ostringstream out;
  out << messages.size() << " validation message(s)";
  for (const ValidationMessage& m : messages) out << "\n  [" << m.id_name << "] " << m.text;
  return out.str();
}

VKAPI_ATTR VkBool32 VKAPI_CALL validation_callback(VkDebugUtilsMessageSeverityFlagBitsEXT severity,
                                                   VkDebugUtilsMessageTypeFlagsEXT /*types*/,
                                                   const VkDebugUtilsMessengerCallbackDataEXT* data,
                                                   void* user_data) {
  auto* log = static_cast<ValidationLog*>(user_data);
  log->record(severity, data->pMessageIdName, data->pMessage);
  return VK_FALSE;  // never abort the call: the test decides what a message means
}

}  // namespace avsm::gpu
