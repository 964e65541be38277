#pragma once
// Light-space capture of hair: the strands drawn as ribbons facing the light
// (shaders/common/hair_ribbon.glsl, at least one map texel wide with opacity scaled by
// the widening), each fragment appending a short segment whose transmittance is
// one minus the strand's opacity.
#include <rendergraph/graph.h>

#include <vector>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/capture/capture_lists.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_casters.h"

namespace avsm::passes {

class CaptureHairPass {
 public:
  CaptureHairPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Adds "<prefix> capture hair" when there are strands, drawing them into the lists of
  // each of `views` (one; an area light's virtual lights: LightView::list_tile()); returns
  // the lists' new versions.
  CaptureLists add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                            const std::vector<LightView>& views, const StrandCasters& hair) const;

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
};

}  // namespace avsm::passes
