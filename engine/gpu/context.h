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

class PipelineCache;  // gpu/pipeline.h

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

// A device the host application created and keeps owning (Context(const AdoptedDevice&)).
// The host must have created it with at least DeviceRequirements' extensions and
// features, on Vulkan 1.3, with `queue` from a graphics + compute family.
struct AdoptedDevice {
  VkInstance instance = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device = VK_NULL_HANDLE;
  VkDevice device = VK_NULL_HANDLE;
  VkQueue queue = VK_NULL_HANDLE;  // the engine records and submits its passes for this queue
  uint32_t queue_family = 0;
  // Whether the host enabled VK_EXT_debug_utils on the instance (Vulkan cannot be asked):
  // then the engine names its objects and labels its passes.
  bool debug_utils = false;
  // Whether the host enabled VK_LAYER_KHRONOS_validation (and debug utils): then the
  // engine adds its own messenger on the host's instance, so validation_log() collects
  // every message, the host's included. Synchronization validation is on only if the
  // host asked for it when it created the instance (VkValidationFeaturesEXT).
  bool validation_layer = false;
  bool echo_validation = false;
};

// What the engine needs from a device: Vulkan 1.3 with synchronization2 and dynamic
// rendering, VK_KHR_push_descriptor, and (when the device has them) the optional
// features its passes use: 64-bit and fragment-stage atomics for the capture lists,
// geometry shaders, scalar layouts, draw parameters... A host that creates its own
// device puts extensions() and features() into its VkDeviceCreateInfo.
class DeviceRequirements {
 public:
  // Queries `physical`; throws std::runtime_error naming the first missing requirement.
  explicit DeviceRequirements(VkPhysicalDevice physical, const std::vector<std::string>& extra_extensions = {});
  // Not copyable: extensions() and the feature chain point into this object.
  DeviceRequirements(const DeviceRequirements&) = delete;
  DeviceRequirements& operator=(const DeviceRequirements&) = delete;

  // Device extensions to enable (the engine's, then the extra ones); valid while this lives.
  const std::vector<const char*>& extensions() const { return extension_names_; }
  // The feature chain for VkDeviceCreateInfo::pNext (no pEnabledFeatures):
  // VkPhysicalDeviceFeatures2 -> Vulkan 1.3 -> 1.2 -> 1.1 features -> `next`.
  const VkPhysicalDeviceFeatures2* features(void* next = nullptr);

 private:
  std::vector<std::string> extensions_;
  std::vector<const char*> extension_names_;
  VkPhysicalDeviceFeatures2 features_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  VkPhysicalDeviceVulkan11Features features11_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features features12_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan13Features features13_{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
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
  VkDeviceSize min_storage_buffer_offset_alignment = 1;
  // What one resource may be (checked by gpu/device_limits.h before it is made).
  uint32_t max_image_dimension_2d = 4096;  // texels per side of a 2D image
  uint32_t max_image_dimension_3d = 256;   // texels per side of a 3D image
  uint32_t max_image_array_layers = 256;
  uint32_t max_viewport_dimension = 4096;  // the smaller of maxViewportDimensions
  float viewport_bounds_min = -8192.0f;    // viewportBoundsRange[0]
  VkDeviceSize max_buffer_size = ~VkDeviceSize{0};             // Vulkan 1.3 (maintenance4)
  VkDeviceSize max_memory_allocation_size = ~VkDeviceSize{0};  // Vulkan 1.1 (maintenance3)
  bool memory_budget = false;  // VK_EXT_memory_budget: what is left of each heap can be asked
  VkDeviceSize buffer_image_granularity = 1;
  VkDeviceSize non_coherent_atom_size = 1;
  uint32_t subgroup_size = 0;
  bool is_cpu() const { return type == VK_PHYSICAL_DEVICE_TYPE_CPU; }
  bool is_lavapipe() const { return driver_id == VK_DRIVER_ID_MESA_LLVMPIPE; }
};

class Context {
 public:
  // Creates its own instance, picks a device and creates it (destroyed with the context).
  explicit Context(const ContextDesc& desc = {});
  // Wraps a device the host created: the context makes only its own command pool (and
  // a validation messenger, see AdoptedDevice) and destroys only those. Destroy the
  // context before the device, while the host is not submitting to `queue`.
  explicit Context(const AdoptedDevice& adopted);
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
  // False for an adopted device: the host owns instance and device.
  bool owns_device() const { return owns_device_; }
  ValidationLog& validation_log() { return validation_log_; }

  // Index of a memory type allowed by type_bits with all `required` flags; -1 if none.
  int find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const;

  // VK_EXT_debug_utils: names show up in validation messages and RenderDoc-style tools.
  void set_name(uint64_t handle, VkObjectType type, const std::string& name) const;
  template <class Handle>
  void set_name(Handle handle, VkObjectType type, const std::string& name) const {
    set_name(reinterpret_cast<uint64_t>(handle), type, name);
  }
  // Removes a name, before its object is destroyed: the validation layer (1.3.239)
  // otherwise keeps the names of destroyed objects for good, and a long session that
  // makes and frees resources grew by their names (bench/soak).
  template <class Handle>
  void forget_name(Handle handle, VkObjectType type) const {
    set_name(reinterpret_cast<uint64_t>(handle), type, std::string());
  }
  // Destroys (or frees) a named object, its name first:
  //   ctx.destroy_named(buffer, VK_OBJECT_TYPE_BUFFER, vkDestroyBuffer);
  template <class Handle>
  void destroy_named(Handle handle, VkObjectType type,
                     void (*destroy)(VkDevice, Handle, const VkAllocationCallbacks*)) const {
    forget_name(handle, type);
    destroy(device_, handle, nullptr);
  }
  void begin_label(VkCommandBuffer cmd, const std::string& label) const;
  void end_label(VkCommandBuffer cmd) const;

  // Records with `record`, submits to the graphics queue and waits. For uploads,
  // readbacks, tests and one-off work; frames use their own command buffers. One
  // command buffer is reset and reused for this (a fresh one only when `record` itself
  // calls submit_and_wait): the validation layer (1.3.239) keeps the state of every
  // command buffer ever allocated, so a new one per upload grew a long validated viewer
  // session without bound (bench/soak).
  void submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const;

  // Submits one recorded command buffer and waits for it to finish (on one reused fence).
  void submit_and_wait(VkCommandBuffer cmd) const;

  VkCommandPool command_pool() const { return command_pool_; }
  VkCommandBuffer allocate_command_buffer(const std::string& name) const;

  // The pipelines compiled on this device, kept for later requests (gpu/pipeline.h);
  // destroyed with the context.
  PipelineCache& pipelines() const { return *pipelines_; }

  // Device extension function, loaded at creation.
  PFN_vkCmdPushDescriptorSetKHR cmd_push_descriptor_set = nullptr;

 private:
  void create_instance(const ContextDesc& desc);
  void create_validation_messenger();
  void load_debug_utils();
  void pick_physical_device(const std::string& preference);
  void read_device_info();
  uint32_t universal_queue_family() const;
  void create_device(const ContextDesc& desc);
  void finish_device_setup();

  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  VkDevice device_ = VK_NULL_HANDLE;
  Queue graphics_queue_;
  VkCommandPool command_pool_ = VK_NULL_HANDLE;
  // submit_and_wait's: made on first use, reused after.
  mutable VkCommandBuffer one_shot_cmd_ = VK_NULL_HANDLE;
  mutable bool one_shot_recording_ = false;
  mutable VkFence submit_fence_ = VK_NULL_HANDLE;
  DeviceInfo info_;
  VkPhysicalDeviceMemoryProperties memory_properties_{};
  bool validation_enabled_ = false;
  bool debug_utils_ = false;
  bool owns_device_ = true;
  ValidationLog validation_log_;
  std::unique_ptr<PipelineCache> pipelines_;

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
