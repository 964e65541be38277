#include "passes/camera/quality/shadow_level_overlay_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "shared/passes/camera/quality/shadow_level_overlay.h"

namespace avsm::passes {

ShadowLevelOverlayPass::ShadowLevelOverlayPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/quality/shadow_level_overlay.comp"),
                                       "shadow level overlay")) {}

rg::TextureHandle ShadowLevelOverlayPass::add_to_graph(rg::Graph& graph, rg::TextureHandle image,
                                                       rg::BufferHandle resolution, uint32_t light) {
  struct Data {
    rg::TextureHandle image;
    rg::BufferHandle resolution;
  };
  return graph.add_pass<Data>("shadow level overlay", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) {
        d.image = b.write(image, rg::Usage::StorageReadWrite);
        d.resolution = b.read(resolution, rg::Usage::StorageRead);
      },
      [this, light](const Data& d, rg::PassContext& c) {
        const rg::TextureDesc& size = c.desc(d.image);
        pipeline_.bind(c.cmd());
        gpu::Bindings(ctx_, pipeline_)
            .image("image", c.view(d.image), c.layout(d.image))
            .buffer("Results", c.buffer(d.resolution))
            .push(c.cmd());
        pipeline_.push_constants(c.cmd(), shared::ShadowLevelOverlayPush{{size.width, size.height}, light});
        pipeline_.dispatch_threads(c.cmd(), size.width, size.height);
      }).image;
}

}  // namespace avsm::passes
