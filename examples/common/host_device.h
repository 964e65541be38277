#pragma once
// The host examples' own Vulkan instance and device (examples/host_embed, host_raw): made
// and destroyed here, lent to the engine. The device enables what the engine says it
// needs (avsm::gpu::DeviceRequirements); --validation turns on the Khronos layer with
// synchronization validation and counts its messages.
#include "gpu/context.h"

#include <atomic>
#include <cstdio>
#include <functional>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

namespace host {

inline VKAPI_ATTR VkBool32 VKAPI_CALL count_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user_data) {
  static_cast<std::atomic<int>*>(user_data)->fetch_add(1);
  std::fprintf(stderr, "[host validation] %s: %s\n", data->pMessageIdName ? data->pMessageIdName : "",
               data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

inline void check_vk(VkResult result, const char* what) {
  if (result != VK_SUCCESS) throw std::runtime_error(std::string(what) + " failed: VkResult " + std::to_string(result));
}

// ---------------------------------------------------------------------------------------
// The host's own Vulkan objects: created and destroyed here, lent to the engine.

class HostDevice {
 public:
  explicit HostDevice(bool validation) : validation_(validation) {
    create_instance();
    pick_physical_device();
    create_device();
  }
  ~HostDevice() {
    if (device_) vkDestroyDevice(device_, nullptr);
    if (messenger_) {
      auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
          vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
      destroy(instance_, messenger_, nullptr);
    }
    if (instance_) vkDestroyInstance(instance_, nullptr);
  }
  HostDevice(const HostDevice&) = delete;
  HostDevice& operator=(const HostDevice&) = delete;

  avsm::gpu::AdoptedDevice lend() const {
    return {instance_, physical_device_, device_, queue_, queue_family_, /*debug_utils=*/validation_,
            /*validation_layer=*/validation_, /*echo_validation=*/false};
  }
  VkPhysicalDevice physical_device() const { return physical_device_; }
  VkDevice device() const { return device_; }
  VkQueue queue() const { return queue_; }
  uint32_t queue_family() const { return queue_family_; }
  int validation_messages() const { return messages_.load(); }

 private:
  void create_instance() {
    VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
    app.pApplicationName = "avsm host example";
    app.apiVersion = VK_API_VERSION_1_3;
    std::vector<const char*> layers, extensions;
    VkValidationFeatureEnableEXT sync = VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT;
    VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
    features.enabledValidationFeatureCount = 1;
    features.pEnabledValidationFeatures = &sync;
    VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
    info.pApplicationInfo = &app;
    if (validation_) {
      layers.push_back("VK_LAYER_KHRONOS_validation");
      extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
      info.pNext = &features;
    }
    info.enabledLayerCount = uint32_t(layers.size());
    info.ppEnabledLayerNames = layers.data();
    info.enabledExtensionCount = uint32_t(extensions.size());
    info.ppEnabledExtensionNames = extensions.data();
    check_vk(vkCreateInstance(&info, nullptr, &instance_), "vkCreateInstance");
    if (!validation_) return;
    VkDebugUtilsMessengerCreateInfoEXT messenger{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
    messenger.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
    messenger.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT;
    messenger.pfnUserCallback = count_message;
    messenger.pUserData = &messages_;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    check_vk(create(instance_, &messenger, nullptr, &messenger_), "vkCreateDebugUtilsMessengerEXT");
  }

  // The first Vulkan 1.3 device with a graphics + compute queue, discrete GPUs first.
  void pick_physical_device() {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(instance_, &count, nullptr);
    std::vector<VkPhysicalDevice> devices(count);
    vkEnumeratePhysicalDevices(instance_, &count, devices.data());
    int best_rank = 99;
    for (VkPhysicalDevice candidate : devices) {
      VkPhysicalDeviceProperties props;
      vkGetPhysicalDeviceProperties(candidate, &props);
      const std::optional<uint32_t> family = universal_family(candidate);
      const int rank = props.deviceType == VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU ? 0
                       : props.deviceType == VK_PHYSICAL_DEVICE_TYPE_CPU        ? 2
                                                                                : 1;
      if (props.apiVersion < VK_API_VERSION_1_3 || !family || rank >= best_rank) continue;
      physical_device_ = candidate;
      queue_family_ = *family;
      best_rank = rank;
    }
    if (!physical_device_) throw std::runtime_error("no Vulkan 1.3 device with a graphics + compute queue");
  }

  static std::optional<uint32_t> universal_family(VkPhysicalDevice physical) {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    for (uint32_t i = 0; i < count; ++i)
      if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) return i;
    return std::nullopt;
  }

  // The engine says what it needs; the host could chain its own features after it.
  void create_device() {
    avsm::gpu::DeviceRequirements needs(physical_device_);
    float priority = 1.0f;
    VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
    queue_info.queueFamilyIndex = queue_family_;
    queue_info.queueCount = 1;
    queue_info.pQueuePriorities = &priority;
    VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
    info.pNext = needs.features();
    info.queueCreateInfoCount = 1;
    info.pQueueCreateInfos = &queue_info;
    info.enabledExtensionCount = uint32_t(needs.extensions().size());
    info.ppEnabledExtensionNames = needs.extensions().data();
    check_vk(vkCreateDevice(physical_device_, &info, nullptr, &device_), "vkCreateDevice");
    vkGetDeviceQueue(device_, queue_family_, 0, &queue_);
  }

  bool validation_;
  std::atomic<int> messages_{0};
  VkInstance instance_ = VK_NULL_HANDLE;
  VkDebugUtilsMessengerEXT messenger_ = VK_NULL_HANDLE;
  VkPhysicalDevice physical_device_ = VK_NULL_HANDLE;
  uint32_t queue_family_ = 0;
  VkDevice device_ = VK_NULL_HANDLE;
  VkQueue queue_ = VK_NULL_HANDLE;
};

// Frames in flight, as a real host keeps them: per frame slot a command buffer and a
// fence. The host records frame N+1 while the GPU runs frame N; it reuses a slot only
// after that slot's fence signalled, and then hands the finished frame to `finished`
// (where it calls Shadows::finish_frame for the slot). One slot: a frame at a time.
class HostFrames {
 public:
  struct Slot {
    uint32_t index = 0;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    int frame = -1;  // the frame in flight in this slot; -1: none
  };
  using Finished = std::function<void(const Slot&)>;

  HostFrames(const HostDevice& host, uint32_t frames_in_flight) : host_(host), slots_(frames_in_flight) {
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = host.queue_family();
    check_vk(vkCreateCommandPool(host.device(), &pool_info, nullptr, &pool_), "vkCreateCommandPool");
    for (uint32_t i = 0; i < frames_in_flight; ++i) {
      Slot& slot = slots_[i];
      slot.index = i;
      VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
      alloc.commandPool = pool_;
      alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
      alloc.commandBufferCount = 1;
      check_vk(vkAllocateCommandBuffers(host.device(), &alloc, &slot.cmd), "vkAllocateCommandBuffers");
      VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
      check_vk(vkCreateFence(host.device(), &fence_info, nullptr, &slot.fence), "vkCreateFence");
    }
  }
  ~HostFrames() {
    for (Slot& slot : slots_) {
      if (slot.frame >= 0) vkWaitForFences(host_.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX);
      vkDestroyFence(host_.device(), slot.fence, nullptr);
    }
    vkDestroyCommandPool(host_.device(), pool_, nullptr);
  }
  HostFrames(const HostFrames&) = delete;
  HostFrames& operator=(const HostFrames&) = delete;

  // The slot for frame `frame`, in turn: if it still holds an earlier frame, waits for
  // that frame's fence and hands it to `finished` first.
  Slot& acquire(int frame, const Finished& finished) {
    Slot& slot = slots_[uint32_t(frame) % slots_.size()];
    if (slot.frame >= 0) finish(slot, finished);
    slot.frame = frame;
    return slot;
  }

  // Records the frame into the slot's command buffer (record(cmd)) and submits it on the
  // host's queue; the slot's fence signals when it completes.
  template <class Record>
  void submit(Slot& slot, const Record& record) {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check_vk(vkBeginCommandBuffer(slot.cmd, &begin), "vkBeginCommandBuffer");
    record(slot.cmd);
    check_vk(vkEndCommandBuffer(slot.cmd), "vkEndCommandBuffer");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &slot.cmd;
    check_vk(vkQueueSubmit(host_.queue(), 1, &submit, slot.fence), "frame submission");
  }

  // Waits for the frames still in flight, oldest first (the queue completes them in order).
  void finish_all(int next_frame, const Finished& finished) {
    for (size_t i = 0; i < slots_.size(); ++i) {
      Slot& slot = slots_[(size_t(next_frame) + i) % slots_.size()];
      if (slot.frame >= 0) finish(slot, finished);
    }
  }

 private:
  void finish(Slot& slot, const Finished& finished) {
    check_vk(vkWaitForFences(host_.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX), "vkWaitForFences");
    check_vk(vkResetFences(host_.device(), 1, &slot.fence), "vkResetFences");
    finished(slot);
    slot.frame = -1;
  }

  const HostDevice& host_;
  VkCommandPool pool_ = VK_NULL_HANDLE;
  std::vector<Slot> slots_;
};

}  // namespace host
