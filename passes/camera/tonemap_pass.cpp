#include "passes/camera/tonemap_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "shared/passes/camera/tonemap.h"

namespace avsm::passes {

TonemapPass::TonemapPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx), pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/tonemap.comp"), "tonemap")) {}

rg::TextureHandle TonemapPass::add_to_graph(rg::Graph& graph, rg::TextureHandle hdr, rg::TextureHandle ldr,
                                            float exposure) {
  struct Targets {
    rg::TextureHandle hdr, ldr;
  };
  const Targets& targets = graph.add_pass<Targets>("tonemap", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Targets& d) {
        d.hdr = b.read(hdr, rg::Usage::StorageRead);
        d.ldr = b.write(ldr, rg::Usage::StorageWrite);
      },
      [this, exposure](const Targets& d, rg::PassContext& c) {
        const rg::TextureDesc& size = c.desc(d.ldr);
        pipeline_.bind(c.cmd());
        gpu::Bindings(ctx_, pipeline_)
            .image("hdr", c.view(d.hdr), c.layout(d.hdr))
            .image("ldr", c.view(d.ldr), c.layout(d.ldr))
            .push(c.cmd());
        pipeline_.push_constants(c.cmd(), shared::TonemapPush{exposure});
        pipeline_.dispatch_threads(c.cmd(), size.width, size.height);
      });
  return targets.ldr;
}

}  // namespace avsm::passes
