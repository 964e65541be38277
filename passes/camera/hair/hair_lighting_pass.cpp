#include "passes/camera/hair/hair_lighting_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"
#include "passes/camera/hair/hair_pass.h"
#include "passes/shadows/shadow_maps.h"
#include "shared/passes/camera/hair/hair_lighting.h"

namespace avsm::passes {
namespace {

using Push = shared::HairLightingPush;  // shaders/shared/passes/camera/hair/hair_lighting.h

}  // namespace

HairLightingPass::HairLightingPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      cached_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/hair/hair_lighting.comp"), "hair lighting")),
      reference_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/hair/hair_lighting_reference.comp"),
                                        "hair lighting reference")) {}

rg::BufferHandle HairLightingPass::add_to_graph(rg::Graph& graph, const HairPass& hair, FrameInputs& inputs) {
  const View& view = inputs.view;
  if (hair.point_count() == 0) return {};
  struct Output {
    rg::BufferHandle lights, page_requests;
  };
  const Output& output = graph.add_pass<Output>("hair lighting", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Output& d) {
        if (inputs.cache) inputs.cache->declare_reads(b);
        inputs.shadows.declare_reads(b);
        inputs.fog.declare_reads(b);
        d.page_requests = inputs.ask_for_pages(b);  // the fibres and the smoke in front of them
        const rg::BufferDesc lights{uint64_t(hair.point_count()) * sizeof(HairVertexLight),
                                    "the scene's hair: grooms with fewer strand vertices"};
        d.lights = b.write(b.create_buffer("hair vertex lights", lights), rg::Usage::StorageWrite);
      },
      [this, &hair, inputs, view](const Output& d, rg::PassContext& c) {
        const VolumeCasters volumes = inputs.volumes->casters();
        const bool cached = inputs.cache.has_value();
        const gpu::Pipeline& pipeline = cached ? cached_ : reference_;
        pipeline.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline);
        b.buffer("Points", hair.points())
            .buffer("Tangents", hair.tangents())
            .buffer("VertexLights", c.buffer(d.lights))
            .buffer("Lights", *inputs.lights);
        inputs.shadows.bind(b, c);
        inputs.shadows.bind_page_requests(b, c, d.page_requests);
        inputs.fog.bind(b, c);
        bind_volumes(b, volumes, /*with_atlas=*/cached);
        if (cached) inputs.cache->bind(b, c);
        b.push(c.cmd());
        pipeline.push_constants(c.cmd(), Push{view.view_projection, glm::vec4(view.camera_position, 1.0f),
                                              {view.width, view.height}, hair.point_count(),
                                              inputs.smoke_visible() ? volumes.volume_count : 0u, inputs.light_count,
                                              inputs.shading.step_voxels});
        pipeline.dispatch_threads(c.cmd(), hair.point_count());
      });
  return output.lights;
}

}  // namespace avsm::passes
