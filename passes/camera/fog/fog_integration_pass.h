#pragma once
// The fog's integrated grid (shaders/passes/camera/fog/fog_integration.comp): each froxel
// column walked front to back, each slice's constant medium integrated exactly, texel k
// holding the fog from the camera to slice boundary k + 1 (rgb in-scattered radiance, a
// transmittance), into the frame slot's grid buffer (FogMedia), which persists: a host's
// shading reads it after the pass list. Sets FrameInputs::fog.integrated, which the
// composites then read.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/frame/frame_inputs.h"

namespace avsm::passes {

class FogIntegrationPass {
 public:
  FogIntegrationPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // `froxels`: FogScatteringPass's output.
  void add_to_graph(rg::Graph& graph, rg::TextureHandle froxels, FrameInputs& inputs);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
};

}  // namespace avsm::passes
