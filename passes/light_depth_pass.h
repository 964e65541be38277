#pragma once
// The nearest opaque caster per light texel: the light's meshes rasterised depth-only
// at the map resolution (both faces), for the fixed-memory AVSM build, which enters
// it into each texel's curve as one blocking segment. Shader: shaders/passes/light_depth.vert.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/light_view.h"
#include "passes/shadow_casters.h"

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
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
};

}  // namespace avsm::passes
