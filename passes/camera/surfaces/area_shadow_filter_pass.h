#pragma once
// Area lights' soft shadows on opaque surfaces at the cost of kAreaShadowLookups maps a
// pixel, whatever their virtual lights (shared/area_shadows.h; seed 003 gathers its
// virtual lights interleaved the same way): the opaque pass, with area-light subsets,
// writes each pixel's unshadowed area light and the transmittance of its subset of
// virtual lights; this pass averages that transmittance over the tile of pixels around
// each that looked up every virtual light, on the pixel's own surface, and adds the area
// light times it to the colour. Runs right after the opaque pass, before the fog.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/frame/view.h"

namespace avsm::passes {

class AreaShadowFilterPass {
 public:
  // A neighbour is on the pixel's surface within this share of its distance from the
  // camera of the pixel's tangent plane.
  static constexpr float kPlaneTolerance = 0.01f;

  AreaShadowFilterPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // `color`: the opaque colour (read and written); `area_light` and `depth`: the opaque
  // pass's (OpaquePass::Outputs); `tile`: the widest area_shadow_tile() of the lights
  // that took subsets. Returns the colour's new version.
  rg::TextureHandle add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle area_light,
                                 rg::TextureHandle depth, const View& view, uint32_t tile) const;

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Sampler texel_sampler_;
};

}  // namespace avsm::passes
