#pragma once
// The Vulkan instance, the chosen physical device, the logical device and its
// queues. Everything else in engine/gpu borrows a Context.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

#include "gpu/validation.h"

namespace avsm::gpu {

struct ContextDesc {
  std::string app_name = "avsm";
  // VK_LAYER_KHRONOS_validation with synchronization validation.
  // The environment variable AVSM_VALIDATION=0/1 overrides this.
  bool validation = false;
  // Which physical device: empty picks a discrete GPU when present, else the first
  // other GPU, else a CPU device (lavapipe). Otherwise an index ("1") or a
  // case-insensitive substring of the device name ("llvmpipe", "nvidia").
  // The environment variable AVSM_DEVICE overrides this.
  std::string device;
  // Extra instance / device extensions (a windowed viewer adds surface and swapchain).
  std::vector<std::string> instance_extensions;
  std::vector<std::string> device_extensions;
  // Echo validation messages to stderr as they arrive.
  bool echo_validation = false;
};

struct Queue {
  VkQueue handle = VK_NULL_HANDLE;
  uint32_t family = 0;
};

// Facts about the device that the engine adapts to.
struct DeviceInfo {
  std::string name;
  std::string driver_name;
  std::string driver_info;
  VkPhysicalDeviceType type = VK_PHYSICAL_DEVICE_TYPE_OTHER;
  VkDriverId driver_id = VkDriverId(0);
  uint32_t api_version = 0;
  float timestamp_period_ns = 1.0f;
  uint32_t timestamp_valid_bits = 0;
  VkDeviceSize max_storage_buffer_range = 0;
  VkDeviceSize buffer_image_granularity = 1;
  VkDeviceSize non_coherent_atom_size = 1;
  uint32_t subgroup_size = 0;
  bool is_cpu() const { return type == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  bool is_lavapipe() const { return driver_id == VK_DRIVER_ID_MESA_LLVMPIPE; }
};

class Context {
 public:
  explicit Context(const ContextDesc& desc = {});
  ~Context();
  Context(const Context&) = delete;
  Context& operator=(const Context&) = delete;

  VkInstance instance() const { return instance_; }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_; }
  const DeviceInfo& info() const { return info_; }
  const VkPhysicalDeviceMemoryProperties& memory_properties() const { return memory_properties_; }

  // The universal queue (graphics + compute + transfer). Passes of every queue
  // type run here today; async compute gets its own queue later.
  const Queue& graphics_queue() const { return graphics_queue_; }

  bool validation_enabled() const { return validation_enabled_; }
  ValidationLog& validation_log() { return validation_log_; }

  // Index of a memory type allowed by type_bits with all `required` flags; -1 if none.
  int find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const;

  // VK_EXT_debug_utils: names show up in validation messages and RenderDoc-style tools.
  void set_name(uint64_t handle, VkObjectType type, const std::string& name) const;
  template <class Handle>
  void set_name(Handle handle, VkObjectType type, const std::string& name) const {
    set_name(reinterpret_cast<uint64_t>(handle), type, name);
  }
  void begin_label(VkCommandBuffer cmd, const std::string& label) const;
  void end_label(VkCommandBuffer cmd) const;

  // Records with `record`, submits to the graphics queue and waits. For uploads,
  // readbacks, tests and one-off work; frames use their own command buffers.
  void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;

  // Submits one recorded command buffer and waits for it to finish.
  void submit_and_wait(VkCommandBuffer cmd) const;

  VkCommandPool command_pool() const { return command_pool_; }
  VkCommandBuffer allocate_command_buffer(const std::string& name) const;

  // Device extension function, loaded at creation.
  PFN_vkCmdPushDescriptorSetKHR cmd_push_descriptor_set = nullptr;

 private:
  void create_instance(const ContextDesc& desc);
  void pick_physical_device(const std::string& preference);
  void create_device(const ContextDesc& desc);

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  Queue graphics_queue_;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  DeviceInfo info_;
  VkPhysicalDeviceMemoryProperties memory_properties_{};
  bool validation_enabled_ = false;
  bool debug_utils_ = false;
  ValidationLog validation_log_;

  PFN_vkSetDebugUtilsObjectNameEXT set_object_name_ = nullptr;
  PFN_vkCmdBeginDebugUtilsLabelEXT cmd_begin_label_ = nullptr;
  PFN_vkCmdEndDebugUtilsLabelEXT cmd_end_label_ = nullptr;
};

// Records a debug label around a scope of commands.
class ScopedLabel {
 public:
  ScopedLabel(const Context& ctx, VkCommandBuffer cmd, const std::string& label) : ctx_(ctx), cmd_(cmd) {
    ctx_.begin_label(cmd_, label);
  }
  ~ScopedLabel() { ctx_.end_label(cmd_); }
  ScopedLabel(const ScopedLabel&) = delete;
  ScopedLabel& operator=(const ScopedLabel&) = delete;

 private:
  const Context& ctx_;
  VkCommandBuffer cmd_;
};

// Reads an environment variable; empty when unset.
std::string env_or_empty(const char* name);

}  // namespace avsm::gpu
