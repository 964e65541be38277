#pragma once
// The AVSM shaders built once per node count (AVSM_NODES, shaders/CMakeLists.txt), so
// each keeps its curves in registers (shaders/avsm/avsm_core.glsl).
#include <array>
#include <string>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"

namespace avsm::passes {

inline constexpr std::array<uint32_t, 4> kAvsmNodeCounts = {4, 8, 12, 16};

// `shader`'s compute pipelines per node count, named `name`.
inline gpu::ComputeVariants avsm_node_variants(const gpu::Context& ctx, const gpu::ShaderLibrary& shaders,
                                               const std::string& shader, const std::string& name) {
  std::map<uint32_t, std::vector<uint32_t>> spirv;
  for (uint32_t nodes : kAvsmNodeCounts) spirv[nodes] = shaders.load(shader, {"AVSM_NODES", std::to_string(nodes)});
  return gpu::ComputeVariants(ctx, std::move(spirv), name);
}

}  // namespace avsm::passes
