#pragma once
// The nearest blocking caster per light texel: the light's meshes rasterised depth-only
// at the map resolution (both faces), for the fixed-memory AVSM build, which enters it
// into each texel's curve as one blocking segment. Draws that test alpha go through a
// fragment stage that keeps only fragments letting no light through (masked texels at or
// above the cutoff, blended texels of alpha 1; passes/frame/caster_alpha.h), so a blended
// caster is never a full blocker where it is translucent: the fixed build has no place
// for a partial one and leaves it out there. Shaders: shaders/passes/shadows/fixed_build/light_depth.vert, .frag.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/frame/caster_alpha.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_casters.h"

namespace avsm::passes {

class LightDepthPass {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_D32_SFLOAT;

  LightDepthPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  static uint64_t bytes(uint32_t resolution) { return uint64_t(resolution) * resolution * sizeof(float); }
  // Adds "<prefix> light depth": a new resolution^2 depth texture, cleared to the far
  // plane (1) and drawn with `meshes` (none: it stays clear). Returns it.
  rg::TextureHandle add_to_graph(rg::Graph& graph, const std::string& prefix, const LightView& light,
                                 const MeshCasters& meshes) const;

 private:
  void record(VkCommandBuffer cmd, const LightView& light, const MeshCasters& meshes) const;

  gpu::Context& ctx_;
  gpu::Pipeline depth_only_;    // opaque draws: no fragment stage
  gpu::Pipeline alpha_tested_;  // draws that test alpha
  CasterAlphaTextures alpha_;
};

}  // namespace avsm::passes
