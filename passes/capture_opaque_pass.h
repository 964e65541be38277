#pragma once
// Light-space capture of opaque meshes: every fragment the light sees appends a
// short dense segment (transmittance to 0 over one texel's world size) to its
// texel's list. Rasterised at the map resolution with no attachments; both faces.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/capture_lists.h"
#include "passes/light_view.h"
#include "passes/shadow_casters.h"

namespace avsm::passes {

class CaptureOpaquePass {
 public:
  CaptureOpaquePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Adds "<prefix> capture opaque" when `meshes` has something to draw; returns the lists' new versions.
  CaptureLists add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                            const LightView& light, const MeshCasters& meshes) const;

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
};

}  // namespace avsm::passes
