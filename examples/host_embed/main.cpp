// A host renderer that embeds the engine's adaptive volumetric shadow maps.
//
// The host owns everything but the shadows: it creates the Vulkan instance and device
// itself (enabling what avsm::gpu::DeviceRequirements lists), uploads its own casters
// (a ground quad, a box hovering over it and two sheets of hair strands) as plain
// buffers, builds the engine's frame graph every frame, lets avsm::add_to_graph declare
// the AVSM passes for its one light (avsm::Shadows' pass list), and shades the ground in
// its own compute pass, whose GLSL includes the engine's "common/shadow_lookup.glsl" from
// the installed package. It keeps two frames in flight, recording the next frame while
// the GPU runs the last (HostFrames).
//
// Output: ground.png (the ground seen from above) and, per probe point, the light's
// transmittance there. With --check it compares them with what the geometry predicts
// (the box's shadow, displaced along the light; the hair's partial shadow) and exits
// non-zero when they disagree. Any validation message also fails the run.
//
//   host_embed [--out DIR] [--size PIXELS] [--validation] [--check] [--no-shadows] [--fixed-memory-build]
//              [--point-light]
// --validation (or AVSM_VALIDATION=1) enables VK_LAYER_KHRONOS_validation with
// synchronization validation. --no-shadows binds unshadowed inputs instead of the maps:
// the checks must then fail (the test uses it to show that they can).
#include <avsm/shadows_rendergraph.h>  // avsm/shadows.h and the engine's own frame graph

#include <rendergraph/vulkan/executor.h>
#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <functional>
#include <memory>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "io/image_io.h"

#include "ground_shading.h"

namespace {

// ---------------------------------------------------------------------------------------
// The scene, in world units, y up. The light travels along (1, -2, 0): a point at height h
// casts its shadow h / 2 further along +x.

constexpr float kGroundHalf = 3.0f;                      // ground: x, z in [-3, 3], y = 0
constexpr glm::vec3 kBoxMin{-0.5f, 1.0f, -0.5f};          // the blocker
constexpr glm::vec3 kBoxMax{0.5f, 2.0f, 0.5f};
const glm::vec3 kLightTravel = glm::normalize(glm::vec3(1.0f, -2.0f, 0.0f));
// Hair: two sheets of strands along z, 0.1 apart in height, over x in [-2.6, -1.4],
// z in [-2.6, -1.4]; each strand is 40% opaque and a third of its spacing wide.
constexpr float kHairHeight = 1.5f;
constexpr float kHairMinX = -2.6f, kHairMaxX = -1.4f, kHairMinZ = -2.6f, kHairMaxZ = -1.4f;

// --point-light: a point light up and to the -x side, whose rays cross the box at about
// the sun's slant, so the same checks hold with its own projection.
const glm::vec3 kPointLight{-4.0f, 8.0f, 0.0f};
bool g_point_light = false;

// Where a point at (x, height) in the plane z = 0 lands on the ground along the light.
float ground_landing(float x, float height) {
  if (g_point_light) return kPointLight.x + (x - kPointLight.x) * kPointLight.y / (kPointLight.y - height);
  return x - kLightTravel.x / kLightTravel.y * height;
}

VKAPI_ATTR VkBool32 VKAPI_CALL count_message(VkDebugUtilsMessageSeverityFlagBitsEXT, VkDebugUtilsMessageTypeFlagsEXT,
                                             const VkDebugUtilsMessengerCallbackDataEXT* data, void* user_data) {
  static_cast<std::atomic<int>*>(user_data)->fetch_add(1);
  std::fprintf(stderr, "[host validation] %s: %s\n", data->pMessageIdName ? data->pMessageIdName : "",
               data->pMessage ? data->pMessage : "");
  return VK_FALSE;
}

void check_vk(VkResult result, const char* what) {
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

// ---------------------------------------------------------------------------------------
// The host's casters, in the layouts the caster views document.

struct HostCasters {
  avsm::gpu::Buffer vertices, indices;                      // ground + box
  avsm::gpu::Buffer strand_points, strand_segments, strands;
  avsm::ShadowCasters views;
  avsm::Bounds bounds;
};

void add_quad(std::vector<avsm::CasterVertex>& vertices, std::vector<uint32_t>& indices, const glm::vec3 corners[4],
              const glm::vec3& normal) {
  const uint32_t base = uint32_t(vertices.size());
  for (int i = 0; i < 4; ++i)
    vertices.push_back({{corners[i].x, corners[i].y, corners[i].z}, {normal.x, normal.y, normal.z}, {0.0f, 0.0f}});
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + i);
}

void add_box(std::vector<avsm::CasterVertex>& vertices, std::vector<uint32_t>& indices, glm::vec3 lo, glm::vec3 hi) {
  const glm::vec3 faces[6][4] = {
      {{lo.x, lo.y, lo.z}, {lo.x, lo.y, hi.z}, {lo.x, hi.y, hi.z}, {lo.x, hi.y, lo.z}},  // -x
      {{hi.x, lo.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, hi.y, hi.z}, {hi.x, lo.y, hi.z}},  // +x
      {{lo.x, lo.y, lo.z}, {hi.x, lo.y, lo.z}, {hi.x, lo.y, hi.z}, {lo.x, lo.y, hi.z}},  // -y
      {{lo.x, hi.y, lo.z}, {lo.x, hi.y, hi.z}, {hi.x, hi.y, hi.z}, {hi.x, hi.y, lo.z}},  // +y
      {{lo.x, lo.y, lo.z}, {lo.x, hi.y, lo.z}, {hi.x, hi.y, lo.z}, {hi.x, lo.y, lo.z}},  // -z
      {{lo.x, lo.y, hi.z}, {hi.x, lo.y, hi.z}, {hi.x, hi.y, hi.z}, {lo.x, hi.y, hi.z}},  // +z
  };
  const glm::vec3 normals[6] = {{-1, 0, 0}, {1, 0, 0}, {0, -1, 0}, {0, 1, 0}, {0, 0, -1}, {0, 0, 1}};
  for (int f = 0; f < 6; ++f) add_quad(vertices, indices, faces[f], normals[f]);
}

HostCasters upload_casters(const avsm::gpu::Context& ctx) {
  HostCasters casters;
  std::vector<avsm::CasterVertex> vertices;
  std::vector<uint32_t> indices;
  const glm::vec3 ground[4] = {{-kGroundHalf, 0, -kGroundHalf}, {-kGroundHalf, 0, kGroundHalf},
                               {kGroundHalf, 0, kGroundHalf}, {kGroundHalf, 0, -kGroundHalf}};
  add_quad(vertices, indices, ground, {0, 1, 0});
  add_box(vertices, indices, kBoxMin, kBoxMax);
  for (const avsm::CasterVertex& v : vertices) casters.bounds.extend(glm::vec3(v.position[0], v.position[1], v.position[2]));
  // One draw for the ground, one for the box: the view takes any number of ranges.
  casters.views.meshes.draws = {{0, 6, 0}, {6, uint32_t(indices.size()) - 6, 0}};
  casters.vertices = avsm::gpu::create_buffer_from(ctx, std::move(vertices), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "host vertices");
  casters.indices = avsm::gpu::create_buffer_from(ctx, std::move(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "host indices");
  // Each view's buffer with its size in bytes: add_to_graph checks the draws against them.
  casters.views.meshes.vertices = casters.vertices.handle();
  casters.views.meshes.vertices_size = casters.vertices.size();
  casters.views.meshes.indices = casters.indices.handle();
  casters.views.meshes.indices_size = casters.indices.size();

  // Hair: straight strands along z, 4 segments each, in two sheets.
  std::vector<glm::vec4> points;
  std::vector<avsm::StrandSegment> segments;
  std::vector<avsm::StrandParameters> strands;
  constexpr float kSpacing = 0.03f;
  for (int sheet = 0; sheet < 2; ++sheet) {
    const float y = kHairHeight + 0.1f * float(sheet);
    for (float x = kHairMinX + 0.5f * kSpacing; x < kHairMaxX; x += kSpacing) {
      const uint32_t strand = uint32_t(strands.size());
      strands.push_back({{0.4f, 0.3f, 0.2f, /*opacity=*/0.4f}, /*width=*/kSpacing / 3.0f, {}});
      for (int p = 0; p <= 4; ++p) {
        if (p < 4) segments.push_back({uint32_t(points.size()), strand});
        const glm::vec3 point(x, y, kHairMinZ + (kHairMaxZ - kHairMinZ) * float(p) / 4.0f);
        points.emplace_back(point, 1.0f);
        casters.bounds.extend(point);
      }
    }
  }
  casters.views.strands.segment_count = uint32_t(segments.size());
  casters.strand_points = avsm::gpu::create_buffer_from(ctx, std::move(points), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "host strand points");
  casters.strand_segments = avsm::gpu::create_buffer_from(ctx, std::move(segments), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "host strand segments");
  casters.strands = avsm::gpu::create_buffer_from(ctx, std::move(strands), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "host strands");
  casters.views.strands.points = casters.strand_points.handle();
  casters.views.strands.points_size = casters.strand_points.size();
  casters.views.strands.segments = casters.strand_segments.handle();
  casters.views.strands.segments_size = casters.strand_segments.size();
  casters.views.strands.strands = casters.strands.handle();
  casters.views.strands.strands_size = casters.strands.size();
  return casters;
}

// ---------------------------------------------------------------------------------------
// The host's frame: its own graph with the engine's shadow passes and its own shading pass.

using avsm::shared::GroundPush;  // shaders/ground_shading.h

class GroundShading {
 public:
  GroundShading(avsm::gpu::Context& ctx, const avsm::Shadows& shadows, uint32_t size)
      : ctx_(ctx),
        pipeline_(avsm::gpu::Pipeline::compute(ctx, shadows.compile_glsl(HOST_SHADER_DIR "/ground_shading.comp"),
                                               "host ground shading")) {
    avsm::gpu::ImageDesc desc;
    desc.width = desc.height = size;
    desc.format = kFormat;
    desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
    desc.name = "host ground image";
    image_ = avsm::gpu::Image::create(ctx, desc);
  }

  // The pass reads the maps (declare_reads) and writes the ground image, which ends the
  // frame ready to be copied out.
  void add_to_graph(rg::Graph& graph, const avsm::ShadowInputs& shadows) {
    const uint32_t size = image_.desc().width;
    // Every frame rewrites it whole, after the frame before (perhaps still running) left it
    // ready to copy: the first write waits for that frame's accesses, the contents discarded.
    rg::ImportState after_previous_frame = rg::ImportState::of(rg::Usage::TransferSrc);
    after_previous_frame.layout = VK_IMAGE_LAYOUT_UNDEFINED;
    rg::TextureHandle image = rg::vulkan::import(graph, "host ground image", image_, after_previous_frame,
                                                 rg::ImportState::of(rg::Usage::TransferSrc));
    struct Data {
      rg::TextureHandle image;
    };
    graph.add_pass<Data>("host ground shading", rg::QueueType::Compute,
        [&](rg::PassBuilder& b, Data& d) {
          d.image = b.write(image, rg::Usage::StorageWrite);
          shadows.declare_reads(b);
        },
        [this, shadows, size](const Data& d, rg::PassContext& c) {
          pipeline_.bind(c.cmd());
          avsm::gpu::Bindings bindings(ctx_, pipeline_);
          bindings.image("ground_image", c.view(d.image), c.layout(d.image));
          shadows.bind(bindings, c);
          bindings.push(c.cmd());
          pipeline_.push_constants(c.cmd(), GroundPush{{-kGroundHalf, -kGroundHalf, 2 * kGroundHalf, 2 * kGroundHalf},
                                                       g_point_light ? glm::vec4(kPointLight, 1.0f)
                                                                     : glm::vec4(-kLightTravel, 0.0f)});
          pipeline_.dispatch_threads(c.cmd(), size, size);
        });
  }

  avsm::gpu::ImageRGBA32F read_back() const {
    return avsm::gpu::read_image(ctx_, image_, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  }

 private:
  static constexpr VkFormat kFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  avsm::gpu::Context& ctx_;
  avsm::gpu::Pipeline pipeline_;
  avsm::gpu::Image image_;
};

// ---------------------------------------------------------------------------------------
// Frames in flight, as a real host keeps them: per frame slot a command buffer, a fence
// and a frame-graph executor (whose transient memory belongs to the frame it recorded).
// The host records frame N+1 while the GPU runs frame N; it reuses a slot only after
// that slot's fence signalled, and then hands the finished frame to Shadows::finish_frame.

constexpr uint32_t kFramesInFlight = 2;

class HostFrames {
 public:
  struct Slot {
    uint32_t index = 0;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    std::unique_ptr<rg::vulkan::Executor> executor;
    int frame = -1;  // the frame in flight in this slot; -1: none
  };
  using Finished = std::function<void(const Slot&)>;

  HostFrames(const HostDevice& host, avsm::gpu::Context& context) : host_(host), slots_(kFramesInFlight) {
    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = host.queue_family();
    check_vk(vkCreateCommandPool(host.device(), &pool_info, nullptr, &pool_), "vkCreateCommandPool");
    for (uint32_t i = 0; i < kFramesInFlight; ++i) {
      Slot& slot = slots_[i];
      slot.index = i;
      VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
      alloc.commandPool = pool_;
      alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
      alloc.commandBufferCount = 1;
      check_vk(vkAllocateCommandBuffers(host.device(), &alloc, &slot.cmd), "vkAllocateCommandBuffers");
      VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
      check_vk(vkCreateFence(host.device(), &fence_info, nullptr, &slot.fence), "vkCreateFence");
      slot.executor = std::make_unique<rg::vulkan::Executor>(context, avsm::gpu::TimestampMode::Exact);
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
    Slot& slot = slots_[uint32_t(frame) % kFramesInFlight];
    if (slot.frame >= 0) finish(slot, finished);
    slot.frame = frame;
    return slot;
  }

  // Records the frame's graph into the slot's command buffer and submits it on the
  // host's queue; the slot's fence signals when it completes.
  void submit(Slot& slot, const rg::Graph& graph) {
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    check_vk(vkBeginCommandBuffer(slot.cmd, &begin), "vkBeginCommandBuffer");
    slot.executor->record(graph, slot.cmd);
    check_vk(vkEndCommandBuffer(slot.cmd), "vkEndCommandBuffer");
    VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
    submit.commandBufferCount = 1;
    submit.pCommandBuffers = &slot.cmd;
    check_vk(vkQueueSubmit(host_.queue(), 1, &submit, slot.fence), "frame submission");
  }

  // Waits for the frames still in flight, oldest first (the queue completes them in order).
  void finish_all(int next_frame, const Finished& finished) {
    for (uint32_t i = 0; i < kFramesInFlight; ++i) {
      Slot& slot = slots_[(uint32_t(next_frame) + i) % kFramesInFlight];
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

// ---------------------------------------------------------------------------------------
// Reading the result: transmittance at world points, and the shadow's extent along x.

struct Options {
  std::filesystem::path out = ".";
  uint32_t size = 128;
  bool validation = false, check = false, shadows = true;
  bool fixed_memory_build = false;  // build the map straight from the casters (avsm::Light)
  bool point_light = false;         // a point light (a cube of six maps) instead of the sun
};

Options parse_options(int argc, char** argv) {
  Options options;
  const char* env = std::getenv("AVSM_VALIDATION");
  options.validation = env && std::strcmp(env, "0") != 0;
  for (int i = 1; i < argc; ++i) {
    const std::string arg = argv[i];
    if (arg == "--out" && i + 1 < argc) options.out = argv[++i];
    else if (arg == "--size" && i + 1 < argc) options.size = uint32_t(std::stoul(argv[++i]));
    else if (arg == "--validation") options.validation = true;
    else if (arg == "--check") options.check = true;
    else if (arg == "--no-shadows") options.shadows = false;
    else if (arg == "--fixed-memory-build") options.fixed_memory_build = true;
    else if (arg == "--point-light") options.point_light = true;
    else throw std::invalid_argument("unknown option '" + arg +
                                     "' (--out DIR --size N --validation --check --no-shadows --fixed-memory-build "
                                     "--point-light)");
  }
  return options;
}

// The picture without the transmittance the shading pass kept in alpha.
avsm::gpu::ImageRGBA32F opaque(avsm::gpu::ImageRGBA32F image) {
  for (size_t i = 3; i < image.pixels.size(); i += 4) image.pixels[i] = 1.0f;
  return image;
}

// The transmittance the shading pass stored (alpha) at the pixel over ground point (x, z).
float transmittance_at(const avsm::gpu::ImageRGBA32F& image, float x, float z) {
  const auto pixel = [&](float world, uint32_t size) {
    const float u = (world + kGroundHalf) / (2 * kGroundHalf);
    return uint32_t(std::clamp(int(u * float(size)), 0, int(size) - 1));
  };
  return image.at(pixel(x, image.width), pixel(z, image.height))[3];
}

// Along the row z, the first and last ground x whose transmittance is below one half.
std::optional<std::pair<float, float>> shadow_extent_along_x(const avsm::gpu::ImageRGBA32F& image, float z) {
  std::optional<std::pair<float, float>> extent;
  const uint32_t row = uint32_t((z + kGroundHalf) / (2 * kGroundHalf) * float(image.height));
  for (uint32_t x = 0; x < image.width; ++x) {
    if (image.at(x, row)[3] >= 0.5f) continue;
    const float world = -kGroundHalf + (float(x) + 0.5f) / float(image.width) * 2 * kGroundHalf;
    if (!extent) extent = std::pair{world, world};
    extent->second = world;
  }
  return extent;
}

struct Checker {
  int failures = 0;
  void expect(bool ok, const std::string& what) {
    std::printf("%s %s\n", ok ? "ok  " : "FAIL", what.c_str());
    if (!ok) ++failures;
  }
};

// What the geometry predicts: under the box's shadow (shifted along x by h / 2 for a
// point at height h) nothing gets through; beside it, and right under the box where
// the slanted light passes, everything does; the hair lets part of it through.
int check_against_geometry(const avsm::gpu::ImageRGBA32F& image) {
  Checker c;
  const float shadow_begin = ground_landing(kBoxMin.x, kBoxMin.y);  // the box's lower -x edge
  const float shadow_end = ground_landing(kBoxMax.x, kBoxMax.y);    // its upper +x edge
  const float in_shadow = transmittance_at(image, 0.5f * (shadow_begin + shadow_end), 0.0f);
  const float beside = transmittance_at(image, shadow_end + 0.8f, 0.0f);
  const float under_box = transmittance_at(image, kBoxMin.x + 0.2f, 0.0f);  // the light passes under the box here
  const float hair_x = ground_landing(0.5f * (kHairMinX + kHairMaxX), kHairHeight + 0.05f);
  const float under_hair = transmittance_at(image, hair_x, 0.5f * (kHairMinZ + kHairMaxZ));
  char line[160];
  std::snprintf(line, sizeof(line), "box shadow at x=%.2f: T=%.3f (expected < 0.1)", 0.5f * (shadow_begin + shadow_end), in_shadow);
  c.expect(in_shadow < 0.1f, line);
  std::snprintf(line, sizeof(line), "beside the shadow at x=%.2f: T=%.3f (expected > 0.9)", shadow_end + 0.8f, beside);
  c.expect(beside > 0.9f, line);
  std::snprintf(line, sizeof(line), "right under the box at x=%.2f: T=%.3f (expected > 0.9: the light is slanted)",
                kBoxMin.x + 0.2f, under_box);
  c.expect(under_box > 0.9f, line);
  std::snprintf(line, sizeof(line), "hair shadow at x=%.2f: T=%.3f (expected partial, 0.15 .. 0.85)", hair_x, under_hair);
  c.expect(under_hair > 0.15f && under_hair < 0.85f, line);
  std::snprintf(line, sizeof(line), "lit pixel much brighter than the shadowed one: %.3f vs %.3f", beside, in_shadow);
  c.expect(beside > 5.0f * std::max(in_shadow, 0.01f), line);

  // The shadow's edges along z = 0: within a map texel and a pixel or two of the prediction.
  constexpr float kTolerance = 0.15f;
  const auto extent = shadow_extent_along_x(image, 0.0f);
  if (!extent) {
    c.expect(false, "a shadow along z = 0");
  } else {
    std::snprintf(line, sizeof(line), "shadow along z = 0 spans x = %.3f .. %.3f (predicted %.3f .. %.3f)", extent->first,
                  extent->second, shadow_begin, shadow_end);
    c.expect(std::abs(extent->first - shadow_begin) < kTolerance && std::abs(extent->second - shadow_end) < kTolerance, line);
  }
  return c.failures;
}

int run(const Options& options) {
  g_point_light = options.point_light;
  HostDevice host(options.validation);
  int failures = 0;
  {
    avsm::gpu::Context context(host.lend());
    avsm::Shadows shadows(context, avsm::ShaderLocation::of_package());
    std::printf("device: %s; shaders: %s\n", context.info().name.c_str(),
                shadows.shader_location().glsl_root.string().c_str());

    HostCasters casters = upload_casters(context);
    avsm::Light sun;
    sun.name = "sun";
    sun.direction = kLightTravel;
    if (options.point_light) {
      sun.name = "point";
      sun.type = avsm::LightType::point;
      sun.position = kPointLight;
      sun.range = 30.0f;
    }
    sun.nodes = 8;
    sun.resolution = 256;
    sun.fixed_memory_build = options.fixed_memory_build;
    shadows.set_light(sun, casters.bounds);
    GroundShading ground(context, shadows, options.size);

    // Each frame declares its shadows into its frame slot, which has its own parameter
    // block and capture counters in the engine.
    shadows.set_frames_in_flight(kFramesInFlight);
    HostFrames frames(host, context);
    const auto finished = [&](const HostFrames::Slot& slot) {
      for (const avsm::LightStats& s : shadows.finish_frame(slot.index))
        std::printf("frame %d light '%s': %u map(s) of %u nodes, %ux%u, %llu segments captured (capacity %llu)%s, "
                    "%llu bytes of fixed build\n", slot.frame, s.name.c_str(), s.maps, s.nodes, s.resolution,
                    s.resolution, (unsigned long long)s.segments_captured, (unsigned long long)s.segment_capacity,
                    s.overflowed ? ", overflowed" : "", (unsigned long long)s.fixed_build_bytes);
    };
    const avsm::Camera camera{glm::vec3(0.0f, 10.0f, 0.0f), 0.8f, options.size};
    // Three frames, two in flight: frame 1 is recorded while frame 0 runs, frame 2 reuses
    // frame 0's slot once its fence signalled (and a grown capture buffer, had it overflowed).
    constexpr int kFrames = 3;
    for (int frame = 0; frame < kFrames; ++frame) {
      HostFrames::Slot& slot = frames.acquire(frame, finished);
      rg::Graph graph;
      const avsm::ShadowInputs maps = options.shadows ? avsm::add_to_graph(graph, shadows, camera, casters.views, slot.index)
                                                      : avsm::unshadowed_inputs(shadows);
      ground.add_to_graph(graph, maps);
      frames.submit(slot, graph);
    }
    frames.finish_all(kFrames, finished);

    const avsm::gpu::ImageRGBA32F image = ground.read_back();
    std::filesystem::create_directories(options.out);
    avsm::io::write_png_srgb(options.out / "ground.png", opaque(image));
    std::printf("wrote %s\n", (options.out / "ground.png").string().c_str());
    if (options.check) failures += check_against_geometry(image);
    const size_t engine_messages = context.validation_log().count();
    if (engine_messages > 0) {
      std::fprintf(stderr, "%s\n", avsm::gpu::describe(context.validation_log().take()).c_str());
      ++failures;
    }
  }
  if (host.validation_messages() > 0) {
    std::fprintf(stderr, "%d validation message(s)\n", host.validation_messages());
    ++failures;
  }
  std::printf("validation: %s\n", options.validation ? "on (with synchronization validation)" : "off");
  return failures;
}

}  // namespace

int main(int argc, char** argv) {
  try {
    const int failures = run(parse_options(argc, argv));
    if (failures == 0) std::printf("host_embed: all checks passed\n");
    else std::printf("host_embed: %d check(s) failed\n", failures);
    return failures == 0 ? 0 : 1;
  } catch (const std::exception& e) {
    std::fprintf(stderr, "host_embed: %s\n", e.what());
    return 2;
  }
}
