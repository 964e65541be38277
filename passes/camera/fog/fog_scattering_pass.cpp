#include "passes/camera/fog/fog_scattering_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"
#include "shared/passes/camera/fog/fog.h"

namespace avsm::passes {
namespace {

using Push = shared::FogPixelsPush;  // shaders/shared/passes/camera/fog/fog.h

}  // namespace

FogScatteringPass::FogScatteringPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/fog/fog_scattering.comp"),
                                       "fog scattering")) {}

rg::TextureHandle FogScatteringPass::add_to_graph(rg::Graph& graph, FrameInputs& inputs) {
  const FogGridSize size = inputs.fog.size;
  struct Output {
    rg::TextureHandle froxels;
    rg::BufferHandle page_requests;
  };
  const Output& output = graph.add_pass<Output>("fog scattering", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Output& d) {
        inputs.shadows.declare_reads(b);
        d.page_requests = inputs.ask_for_pages(b);
        const rg::TextureDesc froxels{size.columns, size.rows, size.slices, 1, 1, kFormat,
                                      "the fog's slices or the image size (or raise its froxel_pixels)"};
        d.froxels = b.write(b.create_texture("fog froxels", froxels), rg::Usage::StorageWrite);
      },
      [this, inputs, size](const Output& d, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline_);
        b.image("scattering_image", c.view(d.froxels), c.layout(d.froxels))
            .buffer("Fog", *inputs.fog.parameters)
            .buffer("Lights", *inputs.lights);
        inputs.shadows.bind(b, c);
        inputs.shadows.bind_page_requests(b, c, d.page_requests);
        b.push(c.cmd());
        const View& view = inputs.view;
        pipeline_.push_constants(c.cmd(), Push{view.inverse_view_projection, {view.width, view.height},
                                               inputs.light_count, 0u});
        pipeline_.dispatch_threads(c.cmd(), size.columns, size.rows, size.slices);
      });
  return output.froxels;
}

}  // namespace avsm::passes
