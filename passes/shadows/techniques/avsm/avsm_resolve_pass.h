#pragma once
// AVSM resolve: per light texel, streams the capture list through the AVSM core
// (insert each segment, compress to N nodes by the smallest-area rule) and
// writes level 0 of the light's map, 4 bytes per node (shaders/shared/map_layouts.h).
// Shader: passes/shadows/techniques/avsm/avsm_resolve.comp.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/techniques/avsm_map_layout.h"
#include "passes/shadows/capture/capture_lists.h"
#include "passes/shadows/techniques/map_build_pass.h"

namespace avsm::passes {

class AvsmResolvePass {
 public:
  AvsmResolvePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Adds "<prefix> avsm resolve"; `map` must hold at least layout.bytes(). Curves clear to
  // far_depth; nodes are stored over [near_depth, far_depth]. Returns the written map.
  rg::BufferHandle add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                rg::BufferHandle map, const AvsmMapLayout& layout, float near_depth,
                                float far_depth) const;

 private:
  MapBuildPass build_;
};

}  // namespace avsm::passes
