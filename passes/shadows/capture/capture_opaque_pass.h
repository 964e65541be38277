#pragma once
// Light-space capture of meshes: every fragment the light sees appends a short dense
// segment (over one texel's world size) to its texel's list, taking transmittance to 0,
// or to 1 - alpha for blended materials; masked ones add nothing below their cutoff
// (passes/frame/caster_alpha.h). Rasterised at the map resolution with no attachments; both faces.
#include <rendergraph/graph.h>

#include <vector>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/frame/caster_alpha.h"
#include "passes/shadows/capture/capture_lists.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_casters.h"

namespace avsm::passes {

class CaptureOpaquePass {
 public:
  CaptureOpaquePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Adds "<prefix> capture opaque" when `meshes` has something to draw, drawing them into the
  // lists of each of `views` (as CaptureHairPass); returns the lists' new versions.
  CaptureLists add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                            const std::vector<LightView>& views, const MeshCasters& meshes) const;

 private:
  // Pushes the pass's bindings with `draw`'s alpha texture.
  void bind(VkCommandBuffer cmd, rg::PassContext& c, const CaptureLists& lists, const MeshCasters& meshes,
            const MeshDraw& draw) const;

  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  CasterAlphaTextures alpha_;
};

}  // namespace avsm::passes
