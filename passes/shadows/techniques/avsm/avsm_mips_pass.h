#pragma once
// AVSM mip chain: each level from the one above by merging the curves of 2x2
// texels (their mean transmittance at every child node depth) and re-compressing
// to N nodes. One pass per light and level ("<prefix> avsm mips level L"), declaring
// (and binding) only the bytes of levels L-1 and L of the map buffer: the frame graph
// plans the barrier between levels. Shader: passes/shadows/techniques/avsm/avsm_mips.comp.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/techniques/avsm_map_layout.h"

namespace avsm::passes {

class AvsmMipsPass {
 public:
  AvsmMipsPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Adds a pass per level above 0, reading and storing nodes over the depth range level 0
  // was stored over; returns the map's new version.
  rg::BufferHandle add_to_graph(rg::Graph& graph, const std::string& prefix, rg::BufferHandle map,
                                const AvsmMapLayout& layout, float near_depth, float far_depth) const;

 private:
  rg::BufferHandle add_level(rg::Graph& graph, const std::string& prefix, rg::BufferHandle map,
                             const AvsmMapLayout& layout, uint32_t level, float near_depth, float far_depth) const;

  gpu::Context& ctx_;
  gpu::ComputeVariants pipelines_;  // per node count
};

}  // namespace avsm::passes
