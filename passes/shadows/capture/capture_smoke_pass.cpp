#include "passes/shadows/capture/capture_smoke_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "passes/camera/volumes/volume_pass.h"
#include "shared/passes/shadows/capture/capture_smoke.h"

namespace avsm::passes {
namespace {

using Push = shared::CaptureSmokePush;  // shaders/shared/passes/shadows/capture/capture_smoke.h

}  // namespace

CaptureSmokePass::CaptureSmokePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      from_atlas_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/shadows/capture/capture_smoke.comp"), "capture smoke")),
      from_nanovdb_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/shadows/capture/capture_smoke_nanovdb.comp"),
                                           "capture smoke nanovdb")) {}

CaptureLists CaptureSmokePass::add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                            const std::vector<LightView>& views, const VolumeCasters& volumes,
                                            uint32_t samples_per_segment) const {
  if (volumes.empty()) return lists;
  return graph.add_pass<CaptureLists>(prefix + " capture smoke", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, CaptureLists& d) { d = append_to_lists(b, lists); },
      [this, views, volumes, samples_per_segment](const CaptureLists& d, rg::PassContext& c) {
        const bool atlas = volumes.has_atlas();
        const gpu::Pipeline& pipeline = atlas ? from_atlas_ : from_nanovdb_;
        pipeline.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline);
        bind_volumes(bindings, volumes, atlas);
        bind_capture_lists(bindings, c, d);
        bindings.push(c.cmd());
        for (const LightView& light : views) {
          pipeline.push_constants(c.cmd(), Push{light.world_from_light, light.depth_plane, light.resolution,
                                                 volumes.volume_count, samples_per_segment, volumes.volume_mask,
                                                 light.raster_origin, light.raster(), 0u, light.list_tile()});
          pipeline.dispatch_threads(c.cmd(), light.resolution, light.resolution);
        }
      });
}

}  // namespace avsm::passes
