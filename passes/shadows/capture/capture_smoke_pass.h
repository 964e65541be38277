#pragma once
// Light-space capture of smoke: one compute thread per light texel marches every
// fog volume along the texel's ray (majorant bricks skip empty space) and appends
// segments with their exact transmittance exp(-optical depth), one per
// `samples_per_segment` march samples. The density comes from the casters' brick atlas
// (one hardware-trilinear fetch a sample) or, for casters without one, from NanoVDB.
// Shaders: shaders/passes/shadows/capture/capture_smoke.comp, capture_smoke_nanovdb.comp.
#include <rendergraph/graph.h>

#include <vector>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/capture/capture_lists.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_casters.h"

namespace avsm::passes {

class CaptureSmokePass {
 public:
  // 16 samples = 4 voxels at the march's quarter-voxel step: short enough that a
  // segment's linear fall is close to the exponential, long enough to keep lists short.
  static constexpr uint32_t kDefaultSamplesPerSegment = 16;

  CaptureSmokePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Adds "<prefix> capture smoke" when there are volumes, marching them for each of `views`
  // (as CaptureHairPass); returns the lists' new versions.
  CaptureLists add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                            const std::vector<LightView>& views, const VolumeCasters& volumes,
                            uint32_t samples_per_segment = kDefaultSamplesPerSegment) const;

 private:
  gpu::Context& ctx_;
  gpu::Pipeline from_atlas_, from_nanovdb_;
};

}  // namespace avsm::passes
