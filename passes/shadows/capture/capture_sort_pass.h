#pragma once
// Optional per-texel sort of a light's capture lists, front to back, so the
// resolve composites segments in a fixed order: with it, the AVSM is the same bit
// for bit from run to run. It relinks the nodes (heads and `next`), which stay in
// place. Shader: shaders/passes/shadows/capture/capture_sort.comp.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/capture/capture_lists.h"

namespace avsm::passes {

class CaptureSortPass {
 public:
  CaptureSortPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Adds "<prefix> sort lists"; returns the new versions of the heads and nodes (the counter is unchanged).
  CaptureLists add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                            uint32_t resolution) const;

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
};

}  // namespace avsm::passes
