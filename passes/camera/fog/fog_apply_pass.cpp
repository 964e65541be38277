#include "passes/camera/fog/fog_apply_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>

#include "gpu/barriers.h"
#include "gpu/context.h"
#include "shared/passes/camera/fog/fog.h"

namespace avsm::passes {
namespace {

using Push = shared::FogPixelsPush;  // shaders/shared/passes/camera/fog/fog.h

constexpr gpu::Access kComputeReadWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                       VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};

// Steps one reference dispatch marches: lavapipe ends a shader's loops after 65535
// iterations in all, and each step looks up `lookups_per_point` maps of up to
// kIterationsPerLookup iterations (bilinear taps over a curve's nodes, with margin).
uint32_t reference_steps_per_dispatch(uint32_t lookups_per_point) {
  constexpr uint32_t kLoopBudget = 65535, kIterationsPerLookup = 64;
  return std::clamp(kLoopBudget / (std::max(lookups_per_point, 1u) * kIterationsPerLookup), 1u,
                    FogApplyPass::kReferenceSteps);
}

}  // namespace

FogApplyPass::FogApplyPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      fast_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/fog/fog_apply.comp"), "fog composite")),
      reference_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/fog/fog_apply_reference.comp"),
                                        "fog composite reference")),
      depth_sampler_(ctx, gpu::texel_sampler_desc("fog depth")) {}

rg::TextureHandle FogApplyPass::add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                             FrameInputs& inputs, bool reference) {
  struct Targets {
    rg::TextureHandle color, depth, state;
    rg::BufferHandle page_requests;
  };
  const Targets& targets = graph.add_pass<Targets>(reference ? "fog composite reference" : "fog composite",
      rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Targets& d) {
        d.depth = b.read(depth, rg::Usage::Sampled);
        if (reference) {
          inputs.shadows.declare_reads(b);
          d.page_requests = inputs.ask_for_pages(b);
          const rg::TextureDesc state{inputs.view.width, inputs.view.height, 1, 1, 1, VK_FORMAT_R32G32B32A32_SFLOAT,
                                      kCameraSizeSetting};
          d.state = b.write(b.create_texture("fog reference state", state), rg::Usage::StorageReadWrite);
        } else {
          inputs.fog.declare_reads(b);
        }
        d.color = b.read_write(color, rg::Usage::StorageReadWrite);
      },
      [this, inputs, reference](const Targets& d, rg::PassContext& c) {
        const View& view = inputs.view;
        const gpu::Pipeline& pipeline = reference ? reference_ : fast_;
        pipeline.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline);
        b.image("color_image", c.view(d.color), c.layout(d.color))
            .image("depth_texture", c.view(d.depth), c.layout(d.depth), depth_sampler_.handle());
        if (reference) {
          b.image("fog_state", c.view(d.state), c.layout(d.state));
          b.buffer("Fog", *inputs.fog.parameters).buffer("Lights", *inputs.lights);
          inputs.shadows.bind(b, c);
          inputs.shadows.bind_page_requests(b, c, d.page_requests);
        } else {
          inputs.fog.bind(b, c);
        }
        b.push(c.cmd());
        if (!reference) {
          pipeline.push_constants(c.cmd(), Push{view.inverse_view_projection, {view.width, view.height},
                                                inputs.light_count, kReferenceSteps, 0u, kReferenceSteps});
          pipeline.dispatch_threads(c.cmd(), view.width, view.height);
          return;
        }
        const uint32_t steps = reference_steps_per_dispatch(inputs.lookups_per_point);
        for (uint32_t first = 0; first < kReferenceSteps; first += steps) {
          if (first > 0) gpu::memory_barrier(c.cmd(), gpu::kComputeWrite, kComputeReadWrite);
          pipeline.push_constants(c.cmd(), Push{view.inverse_view_projection, {view.width, view.height},
                                                inputs.light_count, kReferenceSteps, first, steps});
          pipeline.dispatch_threads(c.cmd(), view.width, view.height);
        }
      });
  return targets.color;
}

}  // namespace avsm::passes
