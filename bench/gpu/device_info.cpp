// avsm_gpu_device_info: the device as the engine sees it, for bench/gpu/check.sh.
//
// Creates the engine's gpu::Context the way the tools do (ContextDesc: device from
// --device or AVSM_DEVICE, validation from --validation or AVSM_VALIDATION) and prints
// the device, driver, API version, the limits engine/gpu/device_limits.h checks every
// resource against, the features DeviceRequirements asks for, the memory heaps (with
// their budget under VK_EXT_memory_budget) and the timestamp mode the engine measures
// (gpu::calibrate_timestamps), as aligned text on stdout and, with --json FILE, as JSON.
//
// Exit status: 0, or 1 when no context could be made (the message says why), 2 on a bad
// command line. A failed timestamp calibration is reported, not fatal.
#include <vulkan/vulkan.h>

#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <exception>
#include <fstream>
#include <memory>
#include <nlohmann/json.hpp>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/gpu_timer.h"
#include "gpu/shader_compiler.h"

namespace {

using nlohmann::ordered_json;
using namespace avsm;

const char* kUsage =
    "usage: avsm_gpu_device_info [--device NAME] [--validation] [--json FILE] [--no-calibrate]\n"
    "  --device NAME   Vulkan device: index or part of its name (env AVSM_DEVICE; default: the engine's pick)\n"
    "  --validation    create the context with validation + synchronization validation\n"
    "  --json FILE     also write everything as JSON to FILE\n"
    "  --no-calibrate  skip the timestamp calibration (which runs one small compute shader)\n";

std::string version_string(uint32_t v) {
  return std::to_string(VK_API_VERSION_MAJOR(v)) + "." + std::to_string(VK_API_VERSION_MINOR(v)) + "." +
         std::to_string(VK_API_VERSION_PATCH(v));
}

// Drivers pack their own version numbers: NVIDIA 10.8.8.6 bits; the rest (Mesa, AMD) as Vulkan does.
std::string driver_version_string(uint32_t vendor, uint32_t v) {
  if (vendor == 0x10DE)
    return std::to_string(v >> 22) + "." + std::to_string((v >> 14) & 0xff) + "." + std::to_string((v >> 6) & 0xff) +
           "." + std::to_string(v & 0x3f);
  return version_string(v);
}

const char* type_string(VkPhysicalDeviceType type) {
  switch (type) {
    case VK_PHYSICAL_DEVICE_TYPE_DISCRETE_GPU: return "discrete GPU";
    case VK_PHYSICAL_DEVICE_TYPE_INTEGRATED_GPU: return "integrated GPU";
    case VK_PHYSICAL_DEVICE_TYPE_VIRTUAL_GPU: return "virtual GPU";
    case VK_PHYSICAL_DEVICE_TYPE_CPU: return "CPU";
    default: return "other";
  }
}

std::string mib(uint64_t bytes) {
  char text[48];
  std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / double(1 << 20));
  return text;
}

std::string hex(uint32_t value) {
  char text[16];
  std::snprintf(text, sizeof(text), "0x%04x", value);
  return text;
}

std::string flags_string(const std::vector<std::pair<uint32_t, const char*>>& names, uint32_t flags) {
  std::string out;
  for (const auto& [bit, name] : names)
    if (flags & bit) {
      if (!out.empty()) out.append("|");  // appended: keeps g++ 12 free of a false -Wrestrict
      out.append(name);
    }
  return out.empty() ? "-" : out;
}

bool has_device_extension(VkPhysicalDevice device, const char* name, uint32_t* spec_version) {
  uint32_t count = 0;
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, nullptr);
  std::vector<VkExtensionProperties> exts(count);
  vkEnumerateDeviceExtensionProperties(device, nullptr, &count, exts.data());
  for (const VkExtensionProperties& e : exts)
    if (std::strcmp(e.extensionName, name) == 0) {
      *spec_version = e.specVersion;
      return true;
    }
  return false;
}

// Text lines in sections, the same figures as the JSON.
struct Printer {
  void section(const std::string& title) { std::printf("%s\n", title.c_str()); }
  void row(const std::string& key, const std::string& value, const std::string& note = "") {
    std::printf("  %-38s %s%s\n", key.c_str(), value.c_str(), note.empty() ? "" : ("   (" + note + ")").c_str());
  }
};

}  // namespace

int main(int argc, char** argv) {
  gpu::ContextDesc desc;
  desc.app_name = "avsm_gpu_device_info";
  desc.echo_validation = true;
  std::string json_path;
  bool calibrate = true;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    auto value = [&]() -> std::string {
      if (i + 1 >= argc) {
        std::fprintf(stderr, "avsm_gpu_device_info: %s needs a value\n%s", arg.c_str(), kUsage);
        std::exit(2);
      }
      return argv[++i];
    };
    if (arg == "--help" || arg == "-h") {
      std::printf("%s", kUsage);
      return 0;
    } else if (arg == "--device") {
      desc.device = value();
    } else if (arg == "--validation") {
      desc.validation = true;
    } else if (arg == "--json") {
      json_path = value();
    } else if (arg == "--no-calibrate") {
      calibrate = false;
    } else {
      std::fprintf(stderr, "avsm_gpu_device_info: unknown option '%s'\n%s", arg.c_str(), kUsage);
      return 2;
    }
  }

  ordered_json out;
  // The validation layer, whether or not this run enables it: the GPU tests need it.
  {
    uint32_t count = 0;
    vkEnumerateInstanceLayerProperties(&count, nullptr);
    std::vector<VkLayerProperties> layers(count);
    vkEnumerateInstanceLayerProperties(&count, layers.data());
    ordered_json layer = {{"available", false}};
    for (const VkLayerProperties& l : layers)
      if (std::strcmp(l.layerName, "VK_LAYER_KHRONOS_validation") == 0)
        layer = {{"available", true}, {"spec_version", version_string(l.specVersion)},
                 {"implementation_version", l.implementationVersion}};
    out["validation_layer"] = layer;
    uint32_t loader = VK_API_VERSION_1_0;
    vkEnumerateInstanceVersion(&loader);
    out["loader_api_version"] = version_string(loader);
  }

  const auto start = std::chrono::steady_clock::now();
  std::unique_ptr<gpu::Context> ctx;
  try {
    ctx = std::make_unique<gpu::Context>(desc);
  } catch (const std::exception& e) {
    std::fprintf(stderr, "avsm_gpu_device_info: error: no engine context: %s\n", e.what());
    out["error"] = e.what();
    if (!json_path.empty()) std::ofstream(json_path) << out.dump(2) << "\n";
    return 1;
  }
  const double context_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  const gpu::DeviceInfo& info = ctx->info();
  const VkPhysicalDevice physical = ctx->physical_device();

  // Every device the instance sees, and which one the engine picked.
  ordered_json devices = ordered_json::array();
  {
    uint32_t count = 0;
    vkEnumeratePhysicalDevices(ctx->instance(), &count, nullptr);
    std::vector<VkPhysicalDevice> all(count);
    vkEnumeratePhysicalDevices(ctx->instance(), &count, all.data());
    for (uint32_t i = 0; i < count; ++i) {
      VkPhysicalDeviceProperties p;
      vkGetPhysicalDeviceProperties(all[i], &p);
      devices.push_back({{"index", i}, {"name", p.deviceName}, {"type", type_string(p.deviceType)},
                         {"api_version", version_string(p.apiVersion)}, {"picked", all[i] == physical}});
    }
  }

  VkPhysicalDevicePushDescriptorPropertiesKHR push{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PUSH_DESCRIPTOR_PROPERTIES_KHR};
  VkPhysicalDeviceVulkan13Properties p13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_PROPERTIES};
  VkPhysicalDeviceVulkan12Properties p12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_PROPERTIES};
  VkPhysicalDeviceVulkan11Properties p11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_PROPERTIES};
  p11.pNext = &p12;
  p12.pNext = &p13;
  p13.pNext = &push;
  VkPhysicalDeviceProperties2 props{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_PROPERTIES_2};
  props.pNext = &p11;
  vkGetPhysicalDeviceProperties2(physical, &props);
  const VkPhysicalDeviceProperties& p = props.properties;
  const VkPhysicalDeviceLimits& l = p.limits;

  VkPhysicalDeviceVulkan13Features f13{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_3_FEATURES};
  VkPhysicalDeviceVulkan12Features f12{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_2_FEATURES};
  VkPhysicalDeviceVulkan11Features f11{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_VULKAN_1_1_FEATURES};
  f13.pNext = &f12;
  f12.pNext = &f11;
  VkPhysicalDeviceFeatures2 features{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_FEATURES_2};
  features.pNext = &f13;
  vkGetPhysicalDeviceFeatures2(physical, &features);
  const VkPhysicalDeviceFeatures& f = features.features;

  const std::string conformance = std::to_string(p12.conformanceVersion.major) + "." +
                                  std::to_string(p12.conformanceVersion.minor) + "." +
                                  std::to_string(p12.conformanceVersion.subminor) + "." +
                                  std::to_string(p12.conformanceVersion.patch);
  out["device"] = {{"name", info.name},
                   {"type", type_string(info.type)},
                   {"vendor_id", hex(p.vendorID)},
                   {"device_id", hex(p.deviceID)},
                   {"driver_name", info.driver_name},
                   {"driver_info", info.driver_info},
                   {"driver_id", int(info.driver_id)},
                   {"driver_version", driver_version_string(p.vendorID, p.driverVersion)},
                   {"driver_version_raw", p.driverVersion},
                   {"api_version", version_string(info.api_version)},
                   {"conformance_version", conformance},
                   {"is_cpu", info.is_cpu()},
                   {"is_lavapipe", info.is_lavapipe()},
                   {"validation_enabled", ctx->validation_enabled()},
                   {"context_create_ms", context_ms}};
  out["devices"] = devices;

  // What engine/gpu/device_limits.h checks every resource against (DeviceInfo), then the
  // rest the passes' shaders and bindings depend on.
  out["limits"] = {
      {"maxStorageBufferRange", info.max_storage_buffer_range},
      {"maxBufferSize", info.max_buffer_size},
      {"maxMemoryAllocationSize", info.max_memory_allocation_size},
      {"maxImageDimension2D", info.max_image_dimension_2d},
      {"maxImageDimension3D", info.max_image_dimension_3d},
      {"maxImageArrayLayers", info.max_image_array_layers},
      {"minStorageBufferOffsetAlignment", info.min_storage_buffer_offset_alignment},
      {"bufferImageGranularity", info.buffer_image_granularity},
      {"nonCoherentAtomSize", info.non_coherent_atom_size},
      {"timestampPeriod_ns", info.timestamp_period_ns},
      {"timestampValidBits", info.timestamp_valid_bits},
      {"timestampComputeAndGraphics", bool(l.timestampComputeAndGraphics)},
      {"subgroupSize", info.subgroup_size},
      {"minSubgroupSize", p13.minSubgroupSize},
      {"maxSubgroupSize", p13.maxSubgroupSize},
      {"subgroupSupportedStages", p11.subgroupSupportedStages},
      {"subgroupSupportedOperations", p11.subgroupSupportedOperations},
      {"maxComputeWorkGroupInvocations", l.maxComputeWorkGroupInvocations},
      {"maxComputeWorkGroupSize", {l.maxComputeWorkGroupSize[0], l.maxComputeWorkGroupSize[1],
                                   l.maxComputeWorkGroupSize[2]}},
      {"maxComputeWorkGroupCount", {l.maxComputeWorkGroupCount[0], l.maxComputeWorkGroupCount[1],
                                    l.maxComputeWorkGroupCount[2]}},
      {"maxComputeSharedMemorySize", l.maxComputeSharedMemorySize},
      {"maxPushConstantsSize", l.maxPushConstantsSize},
      {"maxPushDescriptors", push.maxPushDescriptors},
      {"maxPerStageDescriptorStorageBuffers", l.maxPerStageDescriptorStorageBuffers},
      {"maxPerStageDescriptorStorageImages", l.maxPerStageDescriptorStorageImages},
      {"maxPerStageDescriptorSampledImages", l.maxPerStageDescriptorSampledImages},
      {"maxColorAttachments", l.maxColorAttachments},
      {"maxSamplerAnisotropy", l.maxSamplerAnisotropy},
      {"maxGeometryOutputVertices", l.maxGeometryOutputVertices},
      {"maxGeometryShaderInvocations", l.maxGeometryShaderInvocations},
      {"maxFramebufferLayers", l.maxFramebufferLayers},
  };
  // DeviceRequirements: required (the context could not exist without them), then the
  // optional ones the engine enables when present.
  out["features"] = {
      {"synchronization2 (required)", bool(f13.synchronization2)},
      {"dynamicRendering (required)", bool(f13.dynamicRendering)},
      {"maintenance4", bool(f13.maintenance4)},
      {"fragmentStoresAndAtomics", bool(f.fragmentStoresAndAtomics)},
      {"vertexPipelineStoresAndAtomics", bool(f.vertexPipelineStoresAndAtomics)},
      {"shaderBufferInt64Atomics", bool(f12.shaderBufferInt64Atomics)},
      {"shaderInt64", bool(f.shaderInt64)},
      {"shaderInt16", bool(f.shaderInt16)},
      {"shaderFloat16", bool(f12.shaderFloat16)},
      {"geometryShader", bool(f.geometryShader)},
      {"scalarBlockLayout", bool(f12.scalarBlockLayout)},
      {"storageBuffer8BitAccess", bool(f12.storageBuffer8BitAccess)},
      {"storageBuffer16BitAccess", bool(f11.storageBuffer16BitAccess)},
      {"shaderDrawParameters", bool(f11.shaderDrawParameters)},
      {"timelineSemaphore", bool(f12.timelineSemaphore)},
      {"hostQueryReset", bool(f12.hostQueryReset)},
      {"samplerAnisotropy", bool(f.samplerAnisotropy)},
      {"independentBlend", bool(f.independentBlend)},
      {"largePoints", bool(f.largePoints)},
      {"wideLines", bool(f.wideLines)},
      {"shaderStorageImageExtendedFormats", bool(f.shaderStorageImageExtendedFormats)},
      {"subgroupSizeControl", bool(f13.subgroupSizeControl)},
  };
  ordered_json extensions = ordered_json::object();
  // Required, then used when present (gpu/device_limits.h asks the heaps' budget).
  for (const char* name : {VK_KHR_PUSH_DESCRIPTOR_EXTENSION_NAME, VK_EXT_MEMORY_BUDGET_EXTENSION_NAME}) {
    uint32_t spec = 0;
    const bool present = has_device_extension(physical, name, &spec);
    extensions[name] = present ? ordered_json(spec) : ordered_json(false);
  }
  out["extensions"] = extensions;

  // Memory heaps and types; with VK_EXT_memory_budget, what is left of each heap.
  VkPhysicalDeviceMemoryBudgetPropertiesEXT budget{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_BUDGET_PROPERTIES_EXT};
  VkPhysicalDeviceMemoryProperties2 memory{VK_STRUCTURE_TYPE_PHYSICAL_DEVICE_MEMORY_PROPERTIES_2};
  if (info.memory_budget) memory.pNext = &budget;
  vkGetPhysicalDeviceMemoryProperties2(physical, &memory);
  const VkPhysicalDeviceMemoryProperties& mp = memory.memoryProperties;
  const std::vector<std::pair<uint32_t, const char*>> heap_flags = {
      {VK_MEMORY_HEAP_DEVICE_LOCAL_BIT, "DEVICE_LOCAL"}, {VK_MEMORY_HEAP_MULTI_INSTANCE_BIT, "MULTI_INSTANCE"}};
  const std::vector<std::pair<uint32_t, const char*>> type_flags = {
      {VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT, "DEVICE_LOCAL"}, {VK_MEMORY_PROPERTY_HOST_VISIBLE_BIT, "HOST_VISIBLE"},
      {VK_MEMORY_PROPERTY_HOST_COHERENT_BIT, "HOST_COHERENT"}, {VK_MEMORY_PROPERTY_HOST_CACHED_BIT, "HOST_CACHED"},
      {VK_MEMORY_PROPERTY_LAZILY_ALLOCATED_BIT, "LAZILY_ALLOCATED"}, {VK_MEMORY_PROPERTY_PROTECTED_BIT, "PROTECTED"}};
  ordered_json heaps = ordered_json::array(), types = ordered_json::array();
  for (uint32_t i = 0; i < mp.memoryHeapCount; ++i) {
    ordered_json heap = {{"index", i}, {"size_bytes", mp.memoryHeaps[i].size},
                         {"flags", flags_string(heap_flags, mp.memoryHeaps[i].flags)}};
    if (info.memory_budget) {
      heap["budget_bytes"] = budget.heapBudget[i];
      heap["usage_bytes"] = budget.heapUsage[i];
    }
    heaps.push_back(heap);
  }
  for (uint32_t i = 0; i < mp.memoryTypeCount; ++i)
    types.push_back({{"index", i}, {"heap", mp.memoryTypes[i].heapIndex},
                     {"flags", flags_string(type_flags, mp.memoryTypes[i].propertyFlags)}});
  out["memory"] = {{"budget_extension", info.memory_budget}, {"heaps", heaps}, {"types", types}};

  // The engine's queue: one universal family.
  {
    uint32_t count = 0;
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, nullptr);
    std::vector<VkQueueFamilyProperties> families(count);
    vkGetPhysicalDeviceQueueFamilyProperties(physical, &count, families.data());
    const uint32_t family = ctx->graphics_queue().family;
    const std::vector<std::pair<uint32_t, const char*>> queue_flags = {
        {VK_QUEUE_GRAPHICS_BIT, "GRAPHICS"}, {VK_QUEUE_COMPUTE_BIT, "COMPUTE"}, {VK_QUEUE_TRANSFER_BIT, "TRANSFER"},
        {VK_QUEUE_SPARSE_BINDING_BIT, "SPARSE"}};
    out["queue"] = {{"family", family},
                    {"flags", flags_string(queue_flags, families[family].queueFlags)},
                    {"queue_count", families[family].queueCount},
                    {"families", count}};
  }

  // Which way the engine turns timestamps into pass times on this device.
  if (calibrate) {
    try {
      gpu::ShaderLibrary shaders;
      const gpu::TimestampCalibration c = gpu::calibrate_timestamps(*ctx, shaders);
      out["timestamps"] = {{"mode", gpu::to_string(c.mode)},
                           {"dispatch_ms_timestamps", c.dispatch_ms_timestamps},
                           {"dispatch_ms_host", c.dispatch_ms_host}};
    } catch (const std::exception& e) {
      out["timestamps"] = {{"error", e.what()}};
    }
  }
  const size_t validation_messages = ctx->validation_log().count();
  out["validation_messages"] = validation_messages;

  // The same as aligned text.
  const std::vector<std::pair<uint32_t, const char*>> subgroup_stages = {
      {VK_SHADER_STAGE_VERTEX_BIT, "VERTEX"}, {VK_SHADER_STAGE_GEOMETRY_BIT, "GEOMETRY"},
      {VK_SHADER_STAGE_FRAGMENT_BIT, "FRAGMENT"}, {VK_SHADER_STAGE_COMPUTE_BIT, "COMPUTE"}};
  const std::vector<std::pair<uint32_t, const char*>> subgroup_operations = {
      {VK_SUBGROUP_FEATURE_BASIC_BIT, "BASIC"}, {VK_SUBGROUP_FEATURE_VOTE_BIT, "VOTE"},
      {VK_SUBGROUP_FEATURE_ARITHMETIC_BIT, "ARITHMETIC"}, {VK_SUBGROUP_FEATURE_BALLOT_BIT, "BALLOT"},
      {VK_SUBGROUP_FEATURE_SHUFFLE_BIT, "SHUFFLE"}, {VK_SUBGROUP_FEATURE_SHUFFLE_RELATIVE_BIT, "SHUFFLE_RELATIVE"},
      {VK_SUBGROUP_FEATURE_CLUSTERED_BIT, "CLUSTERED"}, {VK_SUBGROUP_FEATURE_QUAD_BIT, "QUAD"}};
  Printer pr;
  const ordered_json& d = out["device"];
  pr.section("device");
  pr.row("name", info.name, std::string(type_string(info.type)) + ", vendor " + hex(p.vendorID) + ", device " +
                               hex(p.deviceID));
  pr.row("driver", info.driver_name + " " + d["driver_version"].get<std::string>(), info.driver_info);
  pr.row("Vulkan API", version_string(info.api_version), "loader " + out["loader_api_version"].get<std::string>() +
                                                              ", conformance " + conformance);
  pr.row("validation layer",
         out["validation_layer"]["available"].get<bool>()
             ? "available " + out["validation_layer"]["spec_version"].get<std::string>()
             : "MISSING (the GPU tests need VK_LAYER_KHRONOS_validation)",
         ctx->validation_enabled() ? "enabled in this run" : "");
  for (const ordered_json& dev : devices)
    pr.row("device [" + std::to_string(dev["index"].get<uint32_t>()) + "]",
           dev["name"].get<std::string>() + " (" + dev["type"].get<std::string>() + ")",
           dev["picked"].get<bool>() ? "picked" : "");
  pr.row("context created in", std::to_string(int(context_ms)) + " ms");
  pr.section("limits (engine/gpu/device_limits.h checks the first six)");
  for (const auto& [key, value] : out["limits"].items()) {
    std::string note;
    if (value.is_number_unsigned() && value.get<uint64_t>() >= (1u << 20) && key.find("Size") != std::string::npos)
      note = mib(value.get<uint64_t>());
    if (key == "maxStorageBufferRange") note = mib(value.get<uint64_t>()) + "; the shadow maps' budget";
    if (key == "subgroupSupportedStages") note = flags_string(subgroup_stages, value.get<uint32_t>());
    if (key == "subgroupSupportedOperations")  // the passes' shaders use subgroup votes
      note = flags_string(subgroup_operations, value.get<uint32_t>());
    pr.row(key, value.dump(), note);
  }
  pr.section("features (DeviceRequirements: required, else enabled when present)");
  for (const auto& [key, value] : out["features"].items()) pr.row(key, value.get<bool>() ? "yes" : "NO");
  pr.section("extensions");
  for (const auto& [key, value] : out["extensions"].items())
    pr.row(key, value.is_boolean() ? "NO" : "yes (spec " + value.dump() + ")");
  pr.section("memory");
  for (const ordered_json& heap : heaps)
    pr.row("heap " + std::to_string(heap["index"].get<uint32_t>()),
           mib(heap["size_bytes"].get<uint64_t>()) + " " + heap["flags"].get<std::string>(),
           heap.contains("budget_bytes") ? "budget " + mib(heap["budget_bytes"].get<uint64_t>()) + ", used " +
                                               mib(heap["usage_bytes"].get<uint64_t>())
                                         : "");
  for (const ordered_json& type : types)
    pr.row("type " + std::to_string(type["index"].get<uint32_t>()),
           "heap " + std::to_string(type["heap"].get<uint32_t>()) + " " + type["flags"].get<std::string>());
  pr.section("queue and timestamps");
  pr.row("universal queue family", std::to_string(ctx->graphics_queue().family) + " " +
                                       out["queue"]["flags"].get<std::string>());
  if (out.contains("timestamps")) {
    const ordered_json& t = out["timestamps"];
    if (t.contains("error"))
      pr.row("timestamp mode", "calibration FAILED", t["error"].get<std::string>());
    else {
      char note[96];
      std::snprintf(note, sizeof(note), "a dispatch: %.2f ms by timestamps, %.2f ms by the host clock",
                    t["dispatch_ms_timestamps"].get<double>(), t["dispatch_ms_host"].get<double>());
      pr.row("timestamp mode", t["mode"].get<std::string>(), note);
    }
  }
  if (ctx->validation_enabled()) pr.row("validation messages", std::to_string(validation_messages));

  if (!json_path.empty()) {
    std::ofstream file(json_path);
    file << out.dump(2) << "\n";
    if (!file) {
      std::fprintf(stderr, "avsm_gpu_device_info: cannot write %s\n", json_path.c_str());
      return 1;
    }
  }
  return 0;
}
