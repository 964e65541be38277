#pragma once
// The fog over the opaque colour: color = color x T + in-scattered, at each pixel's
// surface, the background seeing the fog's whole depth. Fast: from the integrated grid
// (shaders/passes/camera/fog/fog_apply.comp). Reference (--volume-shading reference):
// each pixel's ray marched in `reference_steps` equal steps with every light's
// transmittance looked up per step (fog_apply_reference.comp), the fast path's yardstick.
// Runs before the smoke's and the hair's composites, which add their own fog.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/frame/frame_inputs.h"

namespace avsm::passes {

class FogApplyPass {
 public:
  static constexpr uint32_t kReferenceSteps = 256;

  FogApplyPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // `depth`: the opaque depth (D32_SFLOAT, output size). Needs inputs.fog.enabled().
  rg::TextureHandle add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                 FrameInputs& inputs, bool reference);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline fast_, reference_;
  gpu::Sampler depth_sampler_;
};

}  // namespace avsm::passes
