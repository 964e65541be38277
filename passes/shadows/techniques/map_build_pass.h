#pragma once
// Builds a comparison technique's per-texel map from a light's capture lists:
// one compute dispatch per light, one thread per texel, with the technique's
// shader (passes/shadows/techniques/avsm/avsm_resolve.comp; the osm and fom builds in their
// folders under passes/shadows/techniques/). All share one push-constant block (the deep
// shadow map's build, several dispatches, has a pass of its own: passes/shadows/techniques/dsm/).
#include <rendergraph/graph.h>

#include <string>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/capture/capture_lists.h"
#include "shared/passes/shadows/techniques/map_build.h"

namespace avsm::passes {

using MapBuildParameters = shared::MapBuildPush;  // shaders/shared/passes/shadows/techniques/map_build.h

class MapBuildPass {
 public:
  // `shader`: e.g. "passes/shadows/techniques/osm/osm_build.comp"; `name`: the pass name after the
  // light prefix. With `per_node_count` the shader is built per AVSM node count
  // (passes/shadows/techniques/avsm/avsm_variants.h) and MapBuildParameters::count picks the variant.
  MapBuildPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const std::string& shader, std::string name,
               bool per_node_count = false);
  // Adds "<prefix> <name>" writing `map` (at least resolution^2 texels of the technique's
  // size).
  rg::BufferHandle add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                rg::BufferHandle map, const MapBuildParameters& parameters) const;

 private:
  gpu::Context& ctx_;
  bool per_node_count_;
  gpu::ComputeVariants pipelines_;  // one per node count, or one (0)
  std::string name_;
};

}  // namespace avsm::passes
