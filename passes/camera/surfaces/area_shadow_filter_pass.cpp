#include "passes/camera/surfaces/area_shadow_filter_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"
#include "shared/passes/camera/surfaces/area_shadow_filter.h"

namespace avsm::passes {

namespace {

using Push = shared::AreaShadowFilterPush;  // shaders/shared/passes/camera/surfaces/area_shadow_filter.h

}  // namespace

AreaShadowFilterPass::AreaShadowFilterPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/surfaces/area_shadow_filter.comp"),
                                       "area shadow filter")),
      texel_sampler_(ctx, gpu::texel_sampler_desc("area shadow filter")) {}

rg::TextureHandle AreaShadowFilterPass::add_to_graph(rg::Graph& graph, rg::TextureHandle color,
                                                     rg::TextureHandle area_light, rg::TextureHandle depth,
                                                     const View& view, uint32_t tile) const {
  struct Targets {
    rg::TextureHandle color, area_light, depth;
  };
  const Targets& targets = graph.add_pass<Targets>("area shadow filter", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Targets& d) {
        d.area_light = b.read(area_light, rg::Usage::Sampled);
        d.depth = b.read(depth, rg::Usage::Sampled);
        d.color = b.read_write(color, rg::Usage::StorageReadWrite);
      },
      [this, view, tile](const Targets& d, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline_);
        b.image("color_image", c.view(d.color), c.layout(d.color))
            .image("area_light_texture", c.view(d.area_light), c.layout(d.area_light), texel_sampler_.handle())
            .image("depth_texture", c.view(d.depth), c.layout(d.depth), texel_sampler_.handle());
        b.push(c.cmd());
        pipeline_.push_constants(c.cmd(), Push{view.inverse_view_projection, glm::vec4(view.camera_position, 1.0f),
                                               {view.width, view.height}, tile, kPlaneTolerance});
        pipeline_.dispatch_threads(c.cmd(), view.width, view.height);
      });
  return targets.color;
}

}  // namespace avsm::passes
