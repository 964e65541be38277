#include "gpu/context.h"

#include <algorithm>
#include <cctype>
#include <cstdlib>
#include <cstring>
#include <sstream>
#include <stdexcept>

#include "gpu/pipeline.h"
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

Context::Context(const AdoptedDevice& adopted) : owns_device_(false) {
  if (!adopted.instance || !adopted.physical_device || !adopted.device || !adopted.queue)
    throw std::invalid_argument("gpu::Context: an adopted device needs its instance, physical device, device and queue");
  if (adopted.validation_layer && !adopted.debug_utils)
    throw std::invalid_argument("gpu::Context: collecting validation messages needs VK_EXT_debug_utils on the instance");
  instance_ = adopted.instance;
  physical_device_ = adopted.physical_device;
  device_ = adopted.device;
  graphics_queue_ = {adopted.queue, adopted.queue_family};
  debug_utils_ = adopted.debug_utils;
  validation_enabled_ = adopted.validation_layer;
  validation_log_.set_echo(adopted.echo_validation || env_flag("AVSM_VALIDATION_ECHO", false));
  read_device_info();
  if (info_.api_version < VK_API_VERSION_1_3)
    throw std::runtime_error("adopted device '" + info_.name + "' lacks Vulkan 1.3");
  if (debug_utils_) load_debug_utils();
  finish_device_setup();
  // Last: nothing after it can throw, so the destructor always gets to destroy it.
  if (validation_enabled_) create_validation_messenger();
}

Context::~Context() {
  if (device_) {
    // An adopted device may be busy with the host's own work on other queues: wait
    // only for the queue the engine submits to.
    if (owns_device_) vkDeviceWaitIdle(device_);
    else vkQueueWaitIdle(graphics_queue_.handle);
    pipelines_.reset();
    vkDestroyFence(device_, submit_fence_, nullptr);
    vkDestroyCommandPool(device_, command_pool_, nullptr);  // frees one_shot_cmd_ too
    if (owns_device_) vkDestroyDevice(device_, nullptr);
  }
  if (messenger_) {
    auto destroy = reinterpret_cast<PFN_vkDestroyDebugUtilsMessengerEXT>(
        vkGetInstanceProcAddr(instance_, "vkDestroyDebugUtilsMessengerEXT"));
    destroy(instance_, messenger_, nullptr);
  }
  if (instance_ && owns_device_) vkDestroyInstance(instance_, nullptr);
}

static VkDebugUtilsMessengerCreateInfoEXT messenger_create_info(ValidationLog& log) {
  VkDebugUtilsMessengerCreateInfoEXT info{VK_STRUCTURE_TYPE_DEBUG_UTILS_MESSENGER_CREATE_INFO_EXT};
  info.messageSeverity = VK_DEBUG_UTILS_MESSAGE_SEVERITY_WARNING_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_SEVERITY_ERROR_BIT_EXT;
  info.messageType = VK_DEBUG_UTILS_MESSAGE_TYPE_VALIDATION_BIT_EXT | VK_DEBUG_UTILS_MESSAGE_TYPE_PERFORMANCE_BIT_EXT;
  info.pfnUserCallback = validation_callback;
  info.pUserData = &log;
  return info;
}

void Context::create_validation_messenger() {
  VkDebugUtilsMessengerCreateInfoEXT info = messenger_create_info(validation_log_);
  auto create = reinterpret_cast<PFN_vkCreateDebugUtilsMessengerEXT>(
      vkGetInstanceProcAddr(instance_, "vkCreateDebugUtilsMessengerEXT"));
  VK_CHECK(create(instance_, &info, nullptr, &messenger_));
}

void Context::load_debug_utils() {
  set_object_name_ = reinterpret_cast<PFN_vkSetDebugUtilsObjectNameEXT>(
      vkGetInstanceProcAddr(instance_, "vkSetDebugUtilsObjectNameEXT"));
  cmd_begin_label_ = reinterpret_cast<PFN_vkCmdBeginDebugUtilsLabelEXT>(
      vkGetInstanceProcAddr(instance_, "vkCmdBeginDebugUtilsLabelEXT"));
  cmd_end_label_ = reinterpret_cast<PFN_vkCmdEndDebugUtilsLabelEXT>(
      vkGetInstanceProcAddr(instance_, "vkCmdEndDebugUtilsLabelEXT"));
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

  // Chained into the instance info too, so messages of vkCreateInstance itself are caught.
  VkDebugUtilsMessengerCreateInfoEXT messenger_info = messenger_create_info(validation_log_);
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

  if (validation_enabled_) create_validation_messenger();
  if (debug_utils_) load_debug_utils();
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
  read_device_info();
}

void Context::read_device_info() {
  VkPhysicalDeviceDriverProperties driver{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_DRIVER_PROPERTIES};
  VkPhysicalDeviceSubgroupProperties subgroup{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_SUBGROUP_PROPERTIES};
  VkPhysicalDeviceMaintenance3Properties maintenance3{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_3_PROPERTIES};
  VkPhysicalDeviceMaintenance4Properties maintenance4{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MAINTENANCE_4_PROPERTIES};
  driver.pNext = &subgroup;
  subgroup.pNext = &maintenance3;
  maintenance3.pNext = &maintenance4;
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
  info_.min_storage_buffer_offset_alignment = limits.minStorageBufferOffsetAlignment;
  info_.max_image_dimension_2d = limits.maxImageDimension2D;
  info_.max_viewport_dimension = std::min(limits.maxViewportDimensions[0], limits.maxViewportDimensions[1]);
  info_.viewport_bounds_min = limits.viewportBoundsRange[0];
  info_.max_image_dimension_3d = limits.maxImageDimension3D;
  info_.max_image_array_layers = limits.maxImageArrayLayers;
  info_.max_memory_allocation_size = maintenance3.maxMemoryAllocationSize;
  if (info_.api_version >= VK_API_VERSION_1_3) info_.max_buffer_size = maintenance4.maxBufferSize;
  info_.memory_budget = has_device_extension(physical_device_, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME);
  info_.buffer_image_granularity = limits.bufferImageGranularity;
  info_.non_coherent_atom_size = limits.nonCoherentAtomSize;
  info_.subgroup_size = subgroup.subgroupSize;
  vkGetPhysicalDeviceMemoryProperties(physical_device_, &memory_properties_);
}

uint32_t Context::universal_queue_family() const {
  uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, families.data());
  for (uint32_t i = 0; i < family_count; ++i)
    if ((families[i].queueFlags & VK_QUEUE_GRAPHICS_BIT) && (families[i].queueFlags & VK_QUEUE_COMPUTE_BIT)) return i;
  throw std::runtime_error("device '" + info_.name + "' has no graphics+compute queue");
}

DeviceRequirements::DeviceRequirements(VkPhysicalDevice physical, const std::vector<std::string>& extra_extensions) {
  VkPhysicalDeviceProperties props;
  vkGetPhysicalDeviceProperties(physical, &props);
  const std::string device = std::string("device '") + props.deviceName + "'";
  if (props.apiVersion < VK_API_VERSION_1_3) throw std::runtime_error(device + " lacks Vulkan 1.3");

  // Ask for what the renderer uses when the device has it; require only the core of it.
  VkPhysicalDeviceVulkan13Features has13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features has12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan11Features has11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  has13.pNext = &has12;
  has12.pNext = &has11;
  VkPhysicalDeviceFeatures2 has{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  has.pNext = &has13;
  vkGetPhysicalDeviceFeatures2(physical, &has);
  if (!has13.synchronization2 || !has13.dynamicRendering)
    throw std::runtime_error(device + " lacks synchronization2 or dynamic rendering");

  features13_.synchronization2 = VK_TRUE;
  features13_.dynamicRendering = VK_TRUE;
  features13_.maintenance4 = has13.maintenance4;
  features12_.timelineSemaphore = has12.timelineSemaphore;
  features12_.hostQueryReset = has12.hostQueryReset;
  features12_.shaderBufferInt64Atomics = has12.shaderBufferInt64Atomics;
  features12_.scalarBlockLayout = has12.scalarBlockLayout;
  features12_.storageBuffer8BitAccess = has12.storageBuffer8BitAccess;
  features12_.shaderFloat16 = has12.shaderFloat16;
  features11_.storageBuffer16BitAccess = has11.storageBuffer16BitAccess;
  features11_.shaderDrawParameters = has11.shaderDrawParameters;
  const VkPhysicalDeviceFeatures& core = has.features;
  VkPhysicalDeviceFeatures& use = features_.features;
  use.geometryShader = core.geometryShader;
  use.fragmentStoresAndAtomics = core.fragmentStoresAndAtomics;
  use.vertexPipelineStoresAndAtomics = core.vertexPipelineStoresAndAtomics;
  use.shaderInt64 = core.shaderInt64;
  use.shaderInt16 = core.shaderInt16;
  use.samplerAnisotropy = core.samplerAnisotropy;
  use.independentBlend = core.independentBlend;
  use.largePoints = core.largePoints;
  use.wideLines = core.wideLines;
  use.shaderStorageImageExtendedFormats = core.shaderStorageImageExtendedFormats;

  extensions_ = {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME};
  extensions_.insert(extensions_.end(), extra_extensions.begin(), extra_extensions.end());
  for (const std::string& ext : extensions_) {
    if (!has_device_extension(physical, ext.c_str())) throw std::runtime_error(device + " lacks extension " + ext);
    extension_names_.push_back(ext.c_str());
  }
}

const VkPhysicalDeviceFeatures2* DeviceRequirements::features(void* next) {
  features_.pNext = &features13_;
  features13_.pNext = &features12_;
  features12_.pNext = &features11_;
  features11_.pNext = next;
  return &features_;
}

void Context::create_device(const ContextDesc& desc) {
  const uint32_t universal = universal_queue_family();
  DeviceRequirements requirements(physical_device_, desc.device_extensions);

  float priority = 1.0f;
  VkDeviceQueueCreateInfo queue_info{VK_STRUCTURE_TYPE_DEVICE_QUEUE_CREATE_INFO};
  queue_info.queueFamilyIndex = universal;
  queue_info.queueCount = 1;
  queue_info.pQueuePriorities = &priority;

  VkDeviceCreateInfo info{VK_STRUCTURE_TYPE_DEVICE_CREATE_INFO};
  info.pNext = requirements.features();
  info.queueCreateInfoCount = 1;
  info.pQueueCreateInfos = &queue_info;
  info.enabledExtensionCount = uint32_t(requirements.extensions().size());
  info.ppEnabledExtensionNames = requirements.extensions().data();
  VK_CHECK(vkCreateDevice(physical_device_, &info, nullptr, &device_));

  graphics_queue_.family = universal;
  vkGetDeviceQueue(device_, graphics_queue_.family, 0, &graphics_queue_.handle);
  set_name(graphics_queue_.handle, VK_OBJECT_TYPE_QUEUE, "universal queue");
  set_name(device_, VK_OBJECT_TYPE_DEVICE, "avsm device");
  finish_device_setup();
}

// What both an owned and an adopted device need: the queue family's timestamp
// bits, the push-descriptor entry point and the context's own command pool.
void Context::finish_device_setup() {
  pipelines_ = std::make_unique<PipelineCache>();
  uint32_t family_count = 0;
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, nullptr);
  std::vector<VkQueueFamilyProperties> families(family_count);
  vkGetPhysicalDeviceQueueFamilyProperties(physical_device_, &family_count, families.data());
  if (graphics_queue_.family >= family_count)
    throw std::runtime_error("device '" + info_.name + "' has no queue family " + std::to_string(graphics_queue_.family));
  info_.timestamp_valid_bits = families[graphics_queue_.family].timestampValidBits;

  cmd_push_descriptor_set = reinterpret_cast<PFN_vkCmdPushDescriptorSetKHR>(
      vkGetDeviceProcAddr(device_, "vkCmdPushDescriptorSetKHR"));
  if (!cmd_push_descriptor_set)
    throw std::runtime_error("device '" + info_.name + "' was created without " VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME);

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
  // An empty name removes it (forget_name); the validation layer erases only on null.
  info.pObjectName = name.empty() ? nullptr : name.c_str();
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
  if (!submit_fence_) {
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(device_, &fence_info, nullptr, &submit_fence_));
    set_name(submit_fence_, VK_OBJECT_TYPE_FENCE, "submit_and_wait fence");
  }
  VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmd_info.commandBuffer = cmd;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmd_info;
  VkResult result = vkQueueSubmit2(graphics_queue_.handle, 1, &submit, submit_fence_);
  if (result == VK_SUCCESS) {
    result = vkWaitForFences(device_, 1, &submit_fence_, VK_TRUE, UINT64_MAX);
    vkResetFences(device_, 1, &submit_fence_);
  }
  VK_CHECK(result);
}

void Context::submit_and_wait(const std::function<void(VkCommandBuffer)>& record) const {
  // The reused command buffer, unless a submit_and_wait inside `record` finds it taken.
  const bool reuse = !one_shot_recording_;
  if (reuse && !one_shot_cmd_) one_shot_cmd_ = allocate_command_buffer("one-shot");
  VkCommandBuffer cmd = reuse ? one_shot_cmd_ : allocate_command_buffer("one-shot (nested)");
  if (reuse) one_shot_recording_ = true;
  const auto release = [&] {
    if (reuse) one_shot_recording_ = false;
    else vkFreeCommandBuffers(device_, command_pool_, 1, &cmd);
  };
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  try {
    VK_CHECK(vkResetCommandBuffer(cmd, 0));
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    record(cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));
    submit_and_wait(cmd);
  } catch (...) {
    release();
    throw;
  }
  release();
}

}  // namespace avsm::gpu
