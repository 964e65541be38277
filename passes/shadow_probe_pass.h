#pragma once
// Transmittance probes: evaluates every light's shadow lookup (the same
// light_transmittance() the camera passes use) at a list of world points and
// leaves the results in a host-readable buffer. For avsm-capture --probe and for
// tests that check a technique against an independent computation.
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <glm/glm.hpp>

#include <vector>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/shadow_maps.h"

namespace avsm::passes {

class ShadowProbePass {
 public:
  ShadowProbePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // Points to probe (uploaded now) for `light_count` lights.
  void set_points(const std::vector<glm::vec3>& points, uint32_t light_count);
  // Adds "shadow probes" reading the maps; the results are ready after the frame.
  void add_to_graph(rg::Graph& graph, rg::vulkan::Executor& executor, const ShadowInputs& shadows);
  // results()[light][point], after the frame completed.
  std::vector<std::vector<float>> results() const;

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Buffer points_, results_;
  uint32_t point_count_ = 0, light_count_ = 0;
};

}  // namespace avsm::passes
