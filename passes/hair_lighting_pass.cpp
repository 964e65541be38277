#include "passes/hair_lighting_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <optional>

#include "gpu/context.h"
#include "passes/hair_pass.h"
#include "passes/shadow_maps.h"

namespace avsm::passes {
namespace {

// Mirrors the push constants of shaders/common/hair_lighting.glsl.
struct Push {
  glm::vec4 camera_position;
  uint32_t point_count;
  uint32_t volume_count;
  uint32_t light_count;
  float step_voxels;
};

}  // namespace

HairLightingPass::HairLightingPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      cached_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/hair_lighting.comp"), "hair lighting")),
      reference_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/hair_lighting_reference.comp"),
                                        "hair lighting reference")) {}

rg::BufferHandle HairLightingPass::add_to_graph(rg::Graph& graph, const HairPass& hair, const View& view,
                                                const VolumePass& volumes, const VolumeLightingCache* cache,
                                                VkSampler cache_sampler, const VolumeShading& shading,
                                                const gpu::Buffer& lights, uint32_t light_count,
                                                const ShadowInputs& shadows, bool fog) {
  if (hair.point_count() == 0) return {};
  struct Output {
    rg::BufferHandle lights;
  };
  const std::optional<VolumeLightingCache> frame_cache = cache ? std::optional(*cache) : std::nullopt;
  const Output& output = graph.add_pass<Output>("hair lighting", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Output& d) {
        shadows.declare_reads(b);
        if (frame_cache) frame_cache->declare_reads(b);
        d.lights = b.write(b.create_buffer("hair vertex lights", {uint64_t(hair.point_count()) * sizeof(HairVertexLight)}),
                           rg::Usage::StorageWrite);
      },
      [this, &hair, &lights, light_count, shadows, frame_cache, cache_sampler, bindings = volumes.bindings(),
       camera = view.camera_position, step = shading.step_voxels, fog](const Output& d, rg::PassContext& c) {
        const gpu::Pipeline& pipeline = frame_cache ? cached_ : reference_;
        pipeline.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline);
        b.buffer(0, hair.points().handle())
            .buffer(1, hair.tangents().handle())
            .buffer(2, c.buffer(d.lights))
            .buffer(3, lights.handle());
        shadows.bind(b, 4, c);
        bindings.bind(b, 8, /*with_atlas=*/frame_cache.has_value());
        if (frame_cache) frame_cache->bind(b, 13, c, cache_sampler);
        b.push(c.cmd());
        pipeline.push_constants(c.cmd(), Push{glm::vec4(camera, 1.0f), hair.point_count(), fog ? bindings.count : 0u,
                                                  light_count, step});
        pipeline.dispatch_threads(c.cmd(), hair.point_count());
      });
  return output.lights;
}

}  // namespace avsm::passes
