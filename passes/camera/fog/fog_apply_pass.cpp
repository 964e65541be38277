#include "passes/camera/fog/fog_apply_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"
#include "shared/passes/camera/fog/fog.h"

namespace avsm::passes {
namespace {

using Push = shared::FogPixelsPush;  // shaders/shared/passes/camera/fog/fog.h

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
    rg::TextureHandle color, depth;
    rg::BufferHandle page_requests;
  };
  const Targets& targets = graph.add_pass<Targets>(reference ? "fog composite reference" : "fog composite",
      rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Targets& d) {
        d.depth = b.read(depth, rg::Usage::Sampled);
        if (reference) {
          inputs.shadows.declare_reads(b);
          d.page_requests = inputs.ask_for_pages(b);
        } else {
          inputs.fog.declare_reads(b);
        }
        d.color = b.read_write(color, rg::Usage::StorageReadWrite);
      },
      [this, inputs, reference](const Targets& d, rg::PassContext& c) {
        const gpu::Pipeline& pipeline = reference ? reference_ : fast_;
        pipeline.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline);
        b.image("color_image", c.view(d.color), c.layout(d.color))
            .image("depth_texture", c.view(d.depth), c.layout(d.depth), depth_sampler_.handle());
        if (reference) {
          b.buffer("Fog", *inputs.fog.parameters).buffer("Lights", *inputs.lights);
          inputs.shadows.bind(b, c);
          inputs.shadows.bind_page_requests(b, c, d.page_requests);
        } else {
          inputs.fog.bind(b, c);
        }
        b.push(c.cmd());
        const View& view = inputs.view;
        pipeline.push_constants(c.cmd(), Push{view.inverse_view_projection, {view.width, view.height},
                                              inputs.light_count, kReferenceSteps});
        pipeline.dispatch_threads(c.cmd(), view.width, view.height);
      });
  return targets.color;
}

}  // namespace avsm::passes
