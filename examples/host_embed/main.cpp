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
// The command line: examples/common/host_run.h.
#include <avsm/shadows_rendergraph.h>  // avsm/shadows.h and the engine's own frame graph

#include <rendergraph/vulkan/executor.h>
#include <rendergraph/vulkan/pass_context.h>

#include <cstdio>
#include <memory>
#include <utility>
#include <vector>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"

#include "host_run.h"

namespace {

using namespace host;  // examples/common: the scene, the checks, the host device and frame loop, the run

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

  // The pass reads the maps (declare_reads), asks paged maps for the pages it reads
  // (declare_page_requests) and writes the ground image, which ends the frame ready to
  // be copied out.
  void add_to_graph(rg::Graph& graph, const avsm::ShadowInputs& shadows) {
    const uint32_t size = image_.desc().width;
    rg::TextureHandle image = rg::vulkan::import(graph, "host ground image", image_, rg::ImportState::none(),
                                                 rg::ImportState::of(rg::Usage::TransferSrc));
    struct Data {
      rg::TextureHandle image;
      rg::BufferHandle page_requests;
    };
    graph.add_pass<Data>("host ground shading", rg::QueueType::Compute,
        [&](rg::PassBuilder& b, Data& d) {
          d.image = b.write(image, rg::Usage::StorageWrite);
          shadows.declare_reads(b);
          d.page_requests = shadows.declare_page_requests(b);
        },
        [this, shadows, size](const Data& d, rg::PassContext& c) {
          pipeline_.bind(c.cmd());
          avsm::gpu::Bindings bindings(ctx_, pipeline_);
          bindings.image("ground_image", c.view(d.image), c.layout(d.image));
          shadows.bind(bindings, c);
          shadows.bind_page_requests(bindings, c, d.page_requests);
          bindings.push(c.cmd());
          pipeline_.push_constants(c.cmd(), ground_push());
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

// Two frames in flight; per slot a frame-graph executor of its own, since an executor's
// transient memory belongs to the frame it recorded.
constexpr uint32_t kFramesInFlight = 2;

int run(const Options& options) {
  HostDevice host(options.validation);
  int failures = 0;
  {
    avsm::gpu::Context context(host.lend());
    avsm::Shadows shadows(context, avsm::ShaderLocation::of_package());
    print_setup(context, shadows);

    HostCasters casters = upload_casters(context);
    shadows.set_light(make_light(options), casters.bounds);
    GroundShading ground(context, shadows, options.size);
    // Each frame declares its shadows into its frame slot, which has its own parameter
    // block and capture counters in the engine.
    shadows.set_frames_in_flight(kFramesInFlight);
    HostFrames frames(host, kFramesInFlight);
    std::vector<std::unique_ptr<rg::vulkan::Executor>> executors;
    for (uint32_t i = 0; i < kFramesInFlight; ++i)
      executors.push_back(std::make_unique<rg::vulkan::Executor>(context, avsm::gpu::TimestampMode::Exact));
    const auto finished = [&](const HostFrames::Slot& slot) { print_stats(slot.frame, shadows.finish_frame(slot.index)); };
    const avsm::Camera camera = make_camera(options);
    // Three frames, two in flight: frame 1 is recorded while frame 0 runs, frame 2 reuses
    // frame 0's slot once its fence signalled (and a grown capture buffer, had it
    // overflowed; a paged map's pages that frame 0's shading asked for).
    constexpr int kFrames = 3;
    for (int frame = 0; frame < kFrames; ++frame) {
      HostFrames::Slot& slot = frames.acquire(frame, finished);
      rg::Graph graph;
      const avsm::ShadowInputs maps = options.shadows ? avsm::add_to_graph(graph, shadows, camera, casters.views, slot.index)
                                                      : avsm::unshadowed_inputs(shadows);
      ground.add_to_graph(graph, maps);
      frames.submit(slot, [&](VkCommandBuffer cmd) { executors[slot.index]->record(graph, cmd); });
    }
    frames.finish_all(kFrames, finished);
    failures += report_picture(ground.read_back(), options, context);
  }
  return failures + report_validation(host, options);
}

}  // namespace

int main(int argc, char** argv) { return host::host_main("host_embed", argc, argv, run); }
