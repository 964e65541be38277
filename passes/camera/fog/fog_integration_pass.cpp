#include "passes/camera/fog/fog_integration_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"

namespace avsm::passes {

FogIntegrationPass::FogIntegrationPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/fog/fog_integration.comp"),
                                       "fog integration")) {}

void FogIntegrationPass::add_to_graph(rg::Graph& graph, rg::TextureHandle froxels, FrameInputs& inputs) {
  const FogGridSize size = inputs.fog.size;
  const gpu::Buffer* parameters = inputs.fog.parameters;
  struct Output {
    rg::TextureHandle froxels, integrated;
  };
  const Output& output = graph.add_pass<Output>("fog integration", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Output& d) {
        d.froxels = b.read(froxels, rg::Usage::StorageRead);
        const rg::TextureDesc integrated{size.columns, size.rows, size.slices, 1, 1, kFormat,
                                         "the fog's froxel_pixels and slices"};
        d.integrated = b.write(b.create_texture("fog integrated", integrated), rg::Usage::StorageWrite);
      },
      [this, parameters, size](const Output& d, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline_);
        b.image("scattering_image", c.view(d.froxels), c.layout(d.froxels))
            .image("integrated_image", c.view(d.integrated), c.layout(d.integrated))
            .buffer("Fog", *parameters);
        b.push(c.cmd());
        pipeline_.dispatch_threads(c.cmd(), size.columns, size.rows);
      });
  inputs.fog.integrated = output.integrated;
}

}  // namespace avsm::passes
