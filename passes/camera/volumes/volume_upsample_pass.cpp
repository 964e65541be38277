#include "passes/camera/volumes/volume_upsample_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"
#include "shared/passes/camera/volumes/volume_upsample.h"

namespace avsm::passes {
namespace {

using Push = shared::VolumeUpsamplePush;  // shaders/shared/passes/camera/volumes/volume_upsample.h

}  // namespace

VolumeUpsamplePass::VolumeUpsamplePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      cached_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/volumes/volume_upsample.comp"), "volume composite")),
      with_lookups_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/volumes/volume_upsample_lookups.comp"),
                                           "volume composite with lookups")),
      nearest_(ctx, gpu::texel_sampler_desc("volume composite")) {}

rg::TextureHandle VolumeUpsamplePass::add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                                   const VolumeMarchImage& march, FrameInputs& inputs) {
  const View& view = inputs.view;
  struct Targets {
    rg::TextureHandle color, depth, scattering, distance;
    rg::BufferHandle page_requests;
  };
  const Targets& targets = graph.add_pass<Targets>("volume composite", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Targets& d) {
        d.depth = b.read(depth, rg::Usage::Sampled);
        d.scattering = b.read(march.scattering, rg::Usage::Sampled);
        d.distance = b.read(march.distance, rg::Usage::Sampled);
        d.page_requests = inputs.declare_volume_access(b);
        inputs.fog.declare_reads(b);
        d.color = b.read_write(color, rg::Usage::StorageReadWrite);
      },
      [this, view, divisor = march.divisor, inputs](const Targets& d, rg::PassContext& c) {
        const rg::TextureDesc& march_size = c.desc(d.scattering);
        const gpu::Pipeline& pipeline = inputs.map_lookups() ? with_lookups_ : cached_;
        pipeline.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline);
        b.image("color_image", c.view(d.color), c.layout(d.color))
            .image("depth_texture", c.view(d.depth), c.layout(d.depth), nearest_.handle())
            .image("scattering_texture", c.view(d.scattering), c.layout(d.scattering), nearest_.handle())
            .image("distance_texture", c.view(d.distance), c.layout(d.distance), nearest_.handle());
        inputs.bind_volumes(b, c, d.page_requests);
        inputs.fog.bind(b, c);
        b.push(c.cmd());
        const bool skipping = inputs.volumes->majorant_skipping();
        pipeline.push_constants(c.cmd(), Push{view.inverse_view_projection, view.camera_position, divisor,
                                               {view.width, view.height}, {march_size.width, march_size.height},
                                               inputs.volumes->volume_count(), inputs.shading.step_voxels,
                                               skipping ? 0u : shared::kMarchNoMajorantSkipping, inputs.light_count});
        pipeline.dispatch_threads(c.cmd(), view.width, view.height);
      });
  return targets.color;
}

}  // namespace avsm::passes
