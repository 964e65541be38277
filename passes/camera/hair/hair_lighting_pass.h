#pragma once
// Per strand vertex: Kajiya-Kay lighting with every light's shadow lookup, and the fog
// between the camera and the vertex (smoke in-scattering and transmittance), which
// HairPass interpolates along each ribbon (shaders/common/hair_lighting.glsl). The fast
// path marches the fog through the lighting cache (hair_lighting.comp); the reference
// path, and a scene without volumes, uses the reference march (hair_lighting_reference.comp).
#include <rendergraph/graph.h>

#include <glm/glm.hpp>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/frame/view.h"
#include "passes/frame/frame_inputs.h"
#include "shared/hair.h"

namespace avsm::passes {

class HairPass;

using shared::HairVertexLight;  // shaders/shared/hair.h

class HairLightingPass {
 public:
  HairLightingPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // One HairVertexLight per strand vertex of `hair`. The fog comes through the frame's
  // lighting cache when `inputs` has one, else from the reference march; the strands
  // see no smoke when it is hidden. Returns an invalid handle when the scene has no hair.
  rg::BufferHandle add_to_graph(rg::Graph& graph, const HairPass& hair, FrameInputs& inputs);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline cached_, reference_;
};

}  // namespace avsm::passes
