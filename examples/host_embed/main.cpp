// A host renderer that embeds the engine's adaptive volumetric shadow maps.
//
// The host owns everything but the shadows: it creates the Vulkan instance and device
// itself (enabling what avsm::gpu::DeviceRequirements lists), uploads its own casters
// (a ground quad, a box hovering over it and two sheets of hair strands) as plain
// buffers, builds its own frame graph every frame, lets avsm::Shadows add the AVSM
// passes for its one light, and shades the ground in its own compute pass, whose GLSL
// includes the engine's "common/shadow_lookup.glsl" from the installed package.
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
#include <avsm/shadows.h>

#include <rendergraph/vulkan/executor.h>
#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <atomic>
#include <cmath>
#include <cstdio>
#include <cstdlib>
#include <cstring>
#include <filesystem>
#include <optional>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "io/image_io.h"

#include "ground_scene.h"
#include "ground_shading.h"
#include "host_device.h"

namespace {

using namespace host;  // examples/common: the scene, the checks, the host device

// ---------------------------------------------------------------------------------------
// The host's casters, in the layouts the caster views document.

struct HostCasters {
  avsm::gpu::Buffer vertices, indices;                      // ground + box
  avsm::gpu::Buffer strand_points, strand_segments, strands;
  avsm::ShadowCasters views;
  avsm::Bounds bounds;
};

HostCasters upload_casters(const avsm::gpu::Context& ctx) {
  CasterArrays arrays = make_casters();
  HostCasters casters;
  casters.bounds = arrays.bounds;
  casters.views.meshes.draws = arrays.draws;
  casters.views.strands.segment_count = uint32_t(arrays.strand_segments.size());
  casters.vertices = avsm::gpu::create_buffer_from(ctx, std::move(arrays.vertices), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "host vertices");
  casters.indices = avsm::gpu::create_buffer_from(ctx, std::move(arrays.indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "host indices");
  casters.strand_points = avsm::gpu::create_buffer_from(ctx, std::move(arrays.strand_points), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "host strand points");
  casters.strand_segments = avsm::gpu::create_buffer_from(ctx, std::move(arrays.strand_segments), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "host strand segments");
  casters.strands = avsm::gpu::create_buffer_from(ctx, std::move(arrays.strands), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "host strands");
  // Each view's buffer with its size in bytes: add_to_graph checks the draws against them.
  casters.views.meshes.vertices = casters.vertices.handle();
  casters.views.meshes.vertices_size = casters.vertices.size();
  casters.views.meshes.indices = casters.indices.handle();
  casters.views.meshes.indices_size = casters.indices.size();
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
    rg::TextureHandle image = rg::vulkan::import(graph, "host ground image", image_, rg::ImportState::none(),
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

// Records the frame into the host's command buffer and submits it on the host's queue.
void submit_frame(const HostDevice& host, VkCommandBuffer cmd, const rg::Graph& graph, rg::vulkan::Executor& executor) {
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  check_vk(vkBeginCommandBuffer(cmd, &begin), "vkBeginCommandBuffer");
  executor.record(graph, cmd);
  check_vk(vkEndCommandBuffer(cmd), "vkEndCommandBuffer");
  VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
  VkFence fence = VK_NULL_HANDLE;
  check_vk(vkCreateFence(host.device(), &fence_info, nullptr, &fence), "vkCreateFence");
  VkSubmitInfo submit{VK_STRUCTURE_TYPE_SUBMIT_INFO};
  submit.commandBufferCount = 1;
  submit.pCommandBuffers = &cmd;
  VkResult result = vkQueueSubmit(host.queue(), 1, &submit, fence);
  if (result == VK_SUCCESS) result = vkWaitForFences(host.device(), 1, &fence, VK_TRUE, UINT64_MAX);
  vkDestroyFence(host.device(), fence, nullptr);
  check_vk(result, "frame submission");
}

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

    VkCommandPoolCreateInfo pool_info{VK_STRUCTURE_TYPE_COMMAND_POOL_CREATE_INFO};
    pool_info.flags = VK_COMMAND_POOL_CREATE_RESET_COMMAND_BUFFER_BIT;
    pool_info.queueFamilyIndex = host.queue_family();
    VkCommandPool pool = VK_NULL_HANDLE;
    check_vk(vkCreateCommandPool(host.device(), &pool_info, nullptr, &pool), "vkCreateCommandPool");
    VkCommandBufferAllocateInfo alloc{VK_STRUCTURE_TYPE_COMMAND_BUFFER_ALLOCATE_INFO};
    alloc.commandPool = pool;
    alloc.level = VK_COMMAND_BUFFER_LEVEL_PRIMARY;
    alloc.commandBufferCount = 1;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    check_vk(vkAllocateCommandBuffers(host.device(), &alloc, &cmd), "vkAllocateCommandBuffers");

    rg::vulkan::Executor executor(context, avsm::gpu::TimestampMode::Exact);
    const avsm::Camera camera{glm::vec3(0.0f, 10.0f, 0.0f), 0.8f, options.size};
    // Two frames: the second reuses the compiled plan (and a grown capture buffer, had the first overflowed).
    for (int frame = 0; frame < 2; ++frame) {
      rg::Graph graph;
      const avsm::ShadowInputs maps = options.shadows ? shadows.add_to_graph(graph, camera, casters.views)
                                                      : shadows.unshadowed_inputs();
      ground.add_to_graph(graph, maps);
      submit_frame(host, cmd, graph, executor);
      for (const avsm::LightStats& s : shadows.finish_frame())
        std::printf("frame %d light '%s': %u map(s) of %u nodes, %ux%u, %llu segments captured (capacity %llu)%s, "
                    "%llu bytes of fixed build\n", frame, s.name.c_str(), s.maps, s.nodes, s.resolution, s.resolution,
                    (unsigned long long)s.segments_captured, (unsigned long long)s.segment_capacity,
                    s.overflowed ? ", overflowed" : "", (unsigned long long)s.fixed_build_bytes);
    }
    vkDestroyCommandPool(host.device(), pool, nullptr);

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
