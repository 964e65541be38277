#include "gpu/context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "gpu/vk_check.h"

namespace avsm::gpu {

std::string env_or_empty(const char* name) {
  const char* value = std::getenv(name);
  return value ? std::string(value) : std::string();
}

static bool env_flag(const char* name, bool fallback) {
  std::string value = env_or_empty(name);
  if (value.empty()) return fallback;
  return !(value == "0" || value == "off" || value == "false" || value == "OFF" || value == "no");
}

static std::string lower(std::string s) {
  std::transform(s.begin(), s.end(), s.begin(), [](unsigned char c) { return std::tolower(c); });
  return s;
}

static bool has_layer(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceLayerProperties(&count, nullptr);
  std::vector<VkLayerProperties> layers(count);
  vkEnumerateInstanceLayerProperties(&count, layers.data());
  return std::any_of(layers.begin(), layers.end(),
                     [&](const VkLayerProperties& l) { return std::strcmp(l.layerName, name) == 0; });
}

static bool has_instance_extension(const char* name) {
  uint32_t count = 0;
  vkEnumerateInstanceExtensionProperties(nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> exts(count);
  vkEnumerateInstanceExtensionProperties(nullptr, &count, exts.data());
  return std::any_of(exts.begin(), exts.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

static bool has_device_extension(VkPhysicalDevice device, const char* name) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> exts(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, exts.data());
  return std::any_of(exts.begin(), exts.end(),
                     [&](const VkExtensionProperties& e) { return std::strcmp(e.extensionName, name) == 0; });
}

Context::Context(const ContextDesc& desc) {
  validation_enabled_ = env_flag("AVSM_VALIDATION", desc.validation);
  validation_log_.set_echo(desc.echo_validation || env_flag("AVSM_VALIDATION_ECHO", false));
  create_instance(desc);
  std::string preference = env_or_empty("AVSM_DEVICE");
  pick_physical_device(preference.empty() ? desc.device : preference);
  create_device(desc);
}

Context::~Context() {
  if (device_) {
    vkDeviceWaitIdle(device_);
    vkDestroyCommandPool(device_, command_pool_, nullptr);
    vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_) vkDestroyInstance(instance_, nullptr);
}

void Context::create_instance(const ContextDesc& desc) {
  std::vector<const char*> layers;
  std::vector<const char*> extensions;
  for (const std::string& ext : desc.instance_extensions) extensions.push_back(ext.c_str());

  debug_utils_ = has_instance_extension(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);
  if (debug_utils_) extensions.push_back(VK_EXT_DEBUG_UTILS_EXTENSION_NAME);

  if (validation_enabled_) {
    if (!has_layer("VK_LAYER_KHRONOS_validation"))
      throw std::runtime_error(
          "validation was requested but VK_LAYER_KHRONOS_validation is not installed "
          "(apt-get install vulkan-validationlayers, or set AVSM_VALIDATION=0)");
    if (!debug_utils_) throw std::runtime_error("validation needs VK_EXT_debug_utils, which the loader lacks");
    layers.push_back("VK_LAYER_KHRONOS_validation");
  }

  VkApplicationInfo app{VK_STRUCTURE_TYPE_APPLICATION_INFO};
  app.pApplicationName = desc.app_name.c_str();
  app.pEngineName = "avsm";
  app.apiVersion = VK_API_VERSION_1_3;

  // Synchronization validation is what catches missing barriers; it is off by default in the layer.
  VkValidationFeatureEnableEXT enables[] = {VK_VALIDATION_FEATURE_ENABLE_SYNCHRONIZATION_VALIDATION_EXT};
  VkValidationFeaturesEXT features{VK_STRUCTURE_TYPE_VALIDATION_FEATURES_EXT};
  features.enabledValidationFeatureCount = 1;
  features.pEnabledValidationFeatures = enables;

  VkDebugUtilsMessengerCreateInfoEXT messenger_info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  messenger_info.messageSeverity =
      VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  messenger_info.messageType =
      VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  messenger_info.pfnUserCallback = validation_callback;
  messenger_info.pUserData = &validation_log_;
  if (validation_enabled_) {
    messenger_info.pNext = &features;
  }

  VkInstanceCreateInfo info{VK_STRUCTURE_TYPE_INSTANCE_CREATE_INFO};
  info.pApplicationInfo = &app;
  info.enabledLayerCount = uint32_t(layers.size());
  info.ppEnabledLayerNames = layers.data();
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  if (validation_enabled_) info.pNext = &messenger_info;
  VK_CHECK(vkCreateInstance(&info, nullptr, &instance_));

  if (validation_enabled_) {
    messenger_info.pNext = nullptr;
    auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
    VK_CHECK(create(instance_, &messenger_info, nullptr, &messenger_));
  }
  if (debug_utils_) {
    set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
        vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
    cmd_begin_label_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
    cmd_end_label_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
        vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
  }
}

static int device_type_rank(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return 0;
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return 1;
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return 2;
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return 3;
    default: return 4;
  }
}

void Context::pick_physical_device(const std::string& preference) {
  uint32_t count = 0;
  VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, nullptr));
  std::vector<VkPhysicalDevice> devices(count);
  VK_CHECK(vkEnumeratePhysicalDevices(instance_, &count, devices.data()));
  if (devices.empty())
    throw std::runtime_error("no Vulkan device found (install mesa-vulkan-drivers for lavapipe)");

  std::vector<VkPhysicalDeviceProperties> props(count);
  for (uint32_t i = 0; i < count; ++i) vkGetPhysicalDeviceProperties(devices[i], &props[i]);

  int chosen = -1;
  if (!preference.empty()) {
    bool is_index = std::all_of(preference.begin(), preference.end(), ::isdigit);
    for (uint32_t i = 0; i < count && chosen < 0; ++i) {
      bool match = is_index ? std::stoul(preference) == i
                            : lower(props[i].deviceName).find(lower(preference)) != std::string::npos;
      if (match) chosen = int(i);
    }
    if (chosen < 0) {
      std::ostringstream message;
      message << "no Vulkan device matches '" << preference << "'; devices:";
      for (uint32_t i = 0; i < count; ++i) message << " [" << i << "] " << props[i].deviceName;
      throw std::runtime_error(message.str());
    }
  } else {
    for (uint32_t i = 0; i < count; ++i)
      if (chosen < 0 || device_type_rank(props[i].deviceType) < device_type_rank(props[chosen].deviceType))
        chosen = int(i);
  }
  physical_device_ = devices[chosen];
  if (props[chosen].apiVersion < VK_API_VERSION_1_3)
    throw std::runtime_error(std::string("device '") + props[chosen].deviceName + "' lacks Vulkan 1.3");

  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  driver.pNext = &subgroup;
  VkPhysicalDeviceProperties2 props2{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props2.pNext = &driver;
  vkGetPhysicalDeviceProperties2(physical_device_, &props2);
  const VkPhysicalDeviceLimits& limits = props2.properties.limits;
  info_.name = props2.properties.deviceName;
  info_.driver_name = driver.driverName;
  info_.driver_info = driver.driverInfo;
  info_.type = props2.properties.deviceType;
  info_.driver_id = driver.driverID;
  info_.api_version = props2.properties.apiVersion;
  info_.timestamp_period_ns = limits.timestampPeriod;
  info_.max_storage_buffer_range = limits.maxStorageBufferRange;
  info_.buffer_image_granularity = limits.bufferImageGranularity;
  info_.non_coherent_atom_size = limits.nonCoherentAtomSize;
  info_.subgroup_size = subgroup.subgroupSize;
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_properties_);
}

void Context::create_device(const ContextDesc& desc) {
  uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, families.data());
  int universal = -1;
  for (uint32_t i = 0; i < family_count && universal < 0; ++i)
    if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT))
      universal = int(i);
  if (universal < 0) throw std::runtime_error("device '" + info_.name + "' has no graphics+compute queue");
  info_.timestamp_valid_bits = families[universal].timestampValidBits;

  // Ask for what the renderer uses when the device has it; require only the core of it.
  VkPhysicalDeviceVulkan13Features has13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features has12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan11Features has11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  has13.pNext = &has12;
  has12.pNext = &has11;
  VkPhysicalDeviceFeatures2 has{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  has.pNext = &has13;
  vkGetPhysicalDeviceFeatures2(physical_device_, &has);
  if (!has13.synchronization2 || !has13.dynamicRendering)
    throw std::runtime_error("device '" + info_.name + "' lacks synchronization2 or dynamic rendering");

  VkPhysicalDeviceVulkan11Features use11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  VkPhysicalDeviceVulkan12Features use12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan13Features use13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceFeatures2 use{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  use.pNext = &use13;
  use13.pNext = &use12;
  use12.pNext = &use11;
  use13.synchronization2 = VK_TRUE;
  use13.dynamicRendering = VK_TRUE;
  use13.maintenance4 = has13.maintenance4;
  use12.timelineSemaphore = has12.timelineSemaphore;
  use12.hostQueryReset = has12.hostQueryReset;
  use12.shaderBufferInt64Atomics = has12.shaderBufferInt64Atomics;
  use12.scalarBlockLayout = has12.scalarBlockLayout;
  use12.storageBuffer8BitAccess = has12.storageBuffer8BitAccess;
  use12.shaderFloat16 = has12.shaderFloat16;
  use11.storageBuffer16BitAccess = has11.storageBuffer16BitAccess;
  use11.shaderDrawParameters = has11.shaderDrawParameters;
  const VkPhysicalDeviceFeatures& core = has.features;
  use.features.geometryShader = core.geometryShader;
  use.features.fragmentStoresAndAtomics = core.fragmentStoresAndAtomics;
  use.features.vertexPipelineStoresAndAtomics = core.vertexPipelineStoresAndAtomics;
  use.features.shaderInt64 = core.shaderInt64;
  use.features.shaderInt16 = core.shaderInt16;
  use.features.samplerAnisotropy = core.samplerAnisotropy;
  use.features.independentBlend = core.independentBlend;
  use.features.largePoints = core.largePoints;
  use.features.wideLines = core.wideLines;
  use.features.shaderStorageImageExtendedFormats = core.shaderStorageImageExtendedFormats;

  std::vector<const char*> extensions = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  for (const std::string& ext : desc.device_extensions) extensions.push_back(ext.c_str());
  for (const char* ext : extensions)
    if (!has_device_extension(physical_device_, ext))
      throw std::runtime_error("device '" + info_.name + "' lacks extension " + ext);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = uint32_t(universal);
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = &use;
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.enabledExtensionCount = uint32_t(extensions.size());
  info.ppEnabledExtensionNames = extensions.data();
  VK_CHECK(vkCreateDevice(physical_device_, &info, nullptr, &device_));

  graphics_queue_.family = uint32_t(universal);
  vkGetDeviceQueue(device_, graphics_queue_.family, 0, &graphics_queue_.handle);
  set_name(graphics_queue_.handle, VK_OBJECT_TYPE_QUEUE, "universal queue");
  set_name(device_, VK_OBJECT_TYPE_DEVICE, "avsm device");

  cmd_push_descriptor_set = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
      vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));

  VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
  pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
  pool_info.queueFamilyIndex = graphics_queue_.family;
  VK_CHECK(vkCreateCommandPool(device_, &pool_info, nullptr, &command_pool_));
  set_name(command_pool_, VK_OBJECT_TYPE_COMMAND_POOL, "context command pool");
}

int Context::find_memory_type(uint32_t type_bits, VkMemoryPropertyFlags required) const {
  for (uint32_t i = 0; i < memory_properties_.memoryTypeCount; ++i)
    if ((type_bits & (1u << i)) && (memory_properties_.memoryTypes[i].propertyFlags & required) == required)
      return int(i);
  return -1;
}

void Context::set_name(uint64_t handle, VkObjectType type, const std::string& name) const {
  if (!set_object_name_ || handle == 0) return;
  VkDebugUtilsObjectNameInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_OBJECT_NAME_INFO_EXT};
  info.objectType = type;
  info.objectHandle = handle;
  info.pObjectName = name.c_str();
  set_object_name_(device_, &info);
}

void Context::begin_label(VkCommandBuffer cmd, const std::string& label) const {
  if (!cmd_begin_label_) return;
  VkDebugUtilsLabelEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_LABEL_EXT};
  info.pLabelName = label.c_str();
  cmd_begin_label_(cmd, &info);
}

void Context::end_label(VkCommandBuffer cmd) const {
  if (cmd_end_label_) cmd_end_label_(cmd);
}

VkCommandBuffer Context::allocate_command_buffer(const std::string& name) const {
  VkCommandBufferAllocateInfo info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
  info.commandPool = command_pool_;
  info.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
  info.commandBufferCount = 1;
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VK_CHECK(vkAllocateCommandBuffers(device_, &info, &cmd));
  set_name(cmd, VK_OBJECT_TYPE_COMMAND_BUFFER, name);
  return cmd;
}

void Context::submit_and_wait(VkCommandBuffer cmd) const {
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  VK_CHECK(vkCreateFence(device_, &fence_info, nullptr, &fence));
  VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmd_info.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmd_info;
  VkResult result = vkQueueSubmit2(graphics_queue_.handle, 1, &submit, fence);
  if (result == VK_SUCCESS) result = vkWaitForFences(device_, 1, &fence, VK_TRUE, UINT64_MAX);
  vkDestroyFence(device_, fence, nullptr);
  VK_CHECK(result);
}

void Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
  VkCommandBuffer cmd = allocate_command_buffer("one-shot");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  try {
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));
    submit_and_wait(cmd);
  } catch (...) {
    vkFreeCommandBuffers(device_, command_pool_, 1, &cmd);
    throw;
  }
  vkFreeCommandBuffers(device_, command_pool_, 1, &cmd);
}

}  // namespace avsm::gpu
