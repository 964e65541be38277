#include "passes/volume_upsample_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"

namespace avsm::passes {
namespace {

// Mirrors the push constants of shaders/passes/volume_upsample.comp.
struct Push {
  glm::mat4 inverse_view_projection;
  glm::vec3 camera_position;
  uint32_t divisor;
  glm::uvec2 output_size;
  glm::uvec2 march_size;
  uint32_t volume_count;
  float step_voxels;
  uint32_t flags;
};
static_assert(sizeof(Push) == 108);
constexpr uint32_t kFlagNoMajorantSkipping = 1u;

}  // namespace

VolumeUpsamplePass::VolumeUpsamplePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/volume_upsample.comp"), "volume composite")),
      nearest_(ctx, {VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE, false,
                     VK_COMPARE_OP_LESS_OR_EQUAL, VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE, "volume composite"}) {}

rg::TextureHandle VolumeUpsamplePass::add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                                   const View& view, const VolumeMarchImage& march,
                                                   const VolumePass& volumes, const VolumeLightingCache& cache,
                                                   VkSampler cache_sampler, const VolumeShading& shading) {
  struct Targets {
    rg::TextureHandle color, depth, scattering, distance;
  };
  const Targets& targets = graph.add_pass<Targets>("volume composite", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Targets& d) {
        d.depth = b.read(depth, rg::Usage::Sampled);
        d.scattering = b.read(march.scattering, rg::Usage::Sampled);
        d.distance = b.read(march.distance, rg::Usage::Sampled);
        cache.declare_reads(b);
        d.color = b.read_write(color, rg::Usage::StorageReadWrite);
      },
      [this, view, divisor = march.divisor, bindings = volumes.bindings(), cache, cache_sampler,
       step = shading.step_voxels, skipping = volumes.majorant_skipping()](const Targets& d, rg::PassContext& c) {
        const rg::TextureDesc& march_size = c.desc(d.scattering);
        pipeline_.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline_);
        b.image(0, c.view(d.color), c.layout(d.color))
            .image(1, c.view(d.depth), c.layout(d.depth), nearest_.handle())
            .image(2, c.view(d.scattering), c.layout(d.scattering), nearest_.handle())
            .image(3, c.view(d.distance), c.layout(d.distance), nearest_.handle());
        bindings.bind(b, 4, /*with_atlas=*/true);
        cache.bind(b, 9, c, cache_sampler);
        b.push(c.cmd());
        pipeline_.push_constants(c.cmd(), Push{view.inverse_view_projection, view.camera_position, divisor,
                                               {view.width, view.height}, {march_size.width, march_size.height},
                                               bindings.count, step, skipping ? 0u : kFlagNoMajorantSkipping});
        pipeline_.dispatch_threads(c.cmd(), view.width, view.height);
      });
  return targets.color;
}

}  // namespace avsm::passes
