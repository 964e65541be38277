#include "passes/shadows/techniques/avsm/avsm_resolve_pass.h"

#include <stdexcept>
#include <string>


namespace avsm::passes {

AvsmResolvePass::AvsmResolvePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : build_(ctx, shaders, "passes/shadows/techniques/avsm/avsm_resolve.comp", "avsm resolve", /*per_node_count=*/true) {}

rg::BufferHandle AvsmResolvePass::add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                               rg::BufferHandle map, const AvsmMapLayout& layout, float near_depth,
                                               float far_depth) const {
  if (layout.nodes < 4 || layout.nodes > 16 || layout.nodes % 4 != 0)
    throw std::invalid_argument("AvsmResolvePass: " + std::to_string(layout.nodes) + " nodes; use 4, 8, 12 or 16");
  return build_.add_to_graph(graph, prefix, lists, map, {layout.resolution, layout.nodes, near_depth, far_depth, 0.0f});
}

}  // namespace avsm::passes
