#pragma once
// The AVSM shaders built once per node count (AVSM_NODES, shaders/CMakeLists.txt), so
// each keeps its curves in registers (shaders/avsm/avsm_core.glsl).
#include <array>
#include <string>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"

namespace avsm::passes {

inline constexpr std::array<uint32_t, 4> kAvsmNodeCounts = {4, 8, 12, 16};

// `shader`'s compute pipelines named `name`: with `per_node_count`, one per AVSM node
// count (get(nodes)); else the one shader for every size (get(0)).
inline gpu::ComputeVariants avsm_node_variants(const gpu::Context& ctx, const gpu::ShaderLibrary& shaders,
                                               const std::string& shader, const std::string& name,
                                               bool per_node_count = true) {
  std::map<uint32_t, std::vector<uint32_t>> spirv;
  if (!per_node_count) spirv[0] = shaders.load(shader);
  else
    for (uint32_t nodes : kAvsmNodeCounts) spirv[nodes] = shaders.load(shader, {"AVSM_NODES", std::to_string(nodes)});
  return gpu::ComputeVariants(ctx, std::move(spirv), name);
}

}  // namespace avsm::passes
