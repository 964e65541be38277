#include "passes/camera/volumes/volume_cached_march_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "shared/passes/camera/volumes/volume_cached_march.h"

namespace avsm::passes {
namespace {

// What sizes the march targets: the setting a message names when one does not fit the device.
constexpr const char* kMarchSizeSetting = "the image size (--width/--height) or raise --volume-resolution-divisor";

using Push = shared::VolumeCachedMarchPush;  // shaders/shared/passes/camera/volumes/volume_cached_march.h

}  // namespace

VolumeCachedMarchPass::VolumeCachedMarchPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      cached_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/volumes/volume_cached_march.comp"), "volume march")),
      with_lookups_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/volumes/volume_cached_march_lookups.comp"),
                                           "volume march with lookups")),
      depth_sampler_(ctx, gpu::texel_sampler_desc("march depth")) {}

VolumeMarchImage VolumeCachedMarchPass::add_to_graph(rg::Graph& graph, rg::TextureHandle depth,
                                                     FrameInputs& inputs) {
  const View& view = inputs.view;
  const uint32_t divisor = uint32_t(inputs.shading.resolution_divisor);
  if (divisor != 1 && divisor != 2 && divisor != 4)
    throw std::invalid_argument("VolumeCachedMarchPass: the resolution divisor must be 1, 2 or 4, got " +
                                std::to_string(divisor));
  const uint32_t width = (view.width + divisor - 1) / divisor, height = (view.height + divisor - 1) / divisor;
  struct Targets {
    rg::TextureHandle depth, scattering, distance;
    rg::BufferHandle page_requests;
  };
  const Targets& targets = graph.add_pass<Targets>("volume march", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Targets& d) {
        d.depth = b.read(depth, rg::Usage::Sampled);
        d.page_requests = inputs.declare_volume_access(b);
        const rg::TextureDesc scattering{width, height, 1, 1, 1, kScatteringFormat, kMarchSizeSetting};
        const rg::TextureDesc distance{width, height, 1, 1, 1, kDistanceFormat, kMarchSizeSetting};
        d.scattering = b.write(b.create_texture("volume march scattering", scattering), rg::Usage::StorageWrite);
        d.distance = b.write(b.create_texture("volume march distance", distance), rg::Usage::StorageWrite);
      },
      [this, view, width, height, divisor, inputs](const Targets& d, rg::PassContext& c) {
        const gpu::Pipeline& pipeline = inputs.map_lookups() ? with_lookups_ : cached_;
        pipeline.bind(c.cmd());
        gpu::Bindings b(ctx_, pipeline);
        b.image("depth_texture", c.view(d.depth), c.layout(d.depth), depth_sampler_.handle())
            .image("scattering_image", c.view(d.scattering), c.layout(d.scattering))
            .image("distance_image", c.view(d.distance), c.layout(d.distance));
        inputs.bind_volumes(b, c, d.page_requests);
        b.push(c.cmd());
        const bool skipping = inputs.volumes->majorant_skipping();
        pipeline.push_constants(c.cmd(), Push{view.inverse_view_projection, view.camera_position,
                                              inputs.volumes->volume_count(), {view.width, view.height},
                                               {width, height}, divisor, inputs.shading.step_voxels,
                                               skipping ? 0u : shared::kMarchNoMajorantSkipping, inputs.light_count});
        pipeline.dispatch_threads(c.cmd(), width, height);
      });
  return {targets.scattering, targets.distance, divisor};
}

}  // namespace avsm::passes
