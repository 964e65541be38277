#include "passes/camera/fog/fog_integration_pass.h"

#include <rendergraph/vulkan/executor.h>
#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"
#include "passes/frame/frames_in_flight.h"

namespace avsm::passes {

FogIntegrationPass::FogIntegrationPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/fog/fog_integration.comp"),
                                       "fog integration")) {}

void FogIntegrationPass::add_to_graph(rg::Graph& graph, rg::TextureHandle froxels, FrameInputs& inputs) {
  const FogGridSize size = inputs.fog.size;
  const gpu::Buffer* parameters = inputs.fog.parameters;
  // Rewritten whole every frame; the frame before (perhaps still running) and the host
  // read it in shaders.
  const rg::ImportState read = rg::ImportState::of(rg::Usage::StorageRead);
  const rg::BufferHandle grid =
      rg::vulkan::import(graph, "fog integrated", *inputs.fog.integrated_buffer, rewritten_after(read), read);
  struct Output {
    rg::TextureHandle froxels;
    rg::BufferHandle integrated;
  };
  const Output& output = graph.add_pass<Output>("fog integration", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Output& d) {
        d.froxels = b.read(froxels, rg::Usage::StorageRead);
        d.integrated = b.write(grid, rg::Usage::StorageWrite);
      },
      [this, parameters, size](const Output& d, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline_);
        b.image("scattering_image", c.view(d.froxels), c.layout(d.froxels))
            .buffer("FogIntegrated", c.buffer(d.integrated))
            .buffer("Fog", *parameters);
        b.push(c.cmd());
        pipeline_.dispatch_threads(c.cmd(), size.columns, size.rows);
      });
  inputs.fog.integrated = output.integrated;
}

}  // namespace avsm::passes
