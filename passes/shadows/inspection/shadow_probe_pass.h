#pragma once
// Transmittance probes: evaluates every light's shadow lookup (the same
// light_transmittance() the camera passes use) at a list of world points and
// leaves the results in a host-readable buffer. For avsm-capture --probe and for
// tests that check a technique against an independent computation.
// Or, in texel-curve mode (set_texel_samples), single level-0 texels' curves at
// chosen light depths, for the technique and for the exact reference side by
// side (avsm-capture --plot-texel).
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <glm/glm.hpp>

#include <vector>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/shadow_maps.h"
#include "shared/passes/shadows/inspection/shadow_probe.h"

namespace avsm::passes {

// One sample of a texel curve: light `light`'s level-0 texel at light depth `depth`.
struct TexelSample {
  uint32_t light = 0;
  glm::uvec2 texel{0};
  float depth = 0.0f;
};

// A texel curve sample's two values.
struct TexelSampleResult {
  float technique;  // the light's technique (its AVSM curve, or the lists when uncompressed)
  float reference;  // the exact curve (capture lists) when the frame kept them, else the technique's
};

class ShadowProbePass {
 public:
  ShadowProbePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // Points to probe (uploaded now) for `light_count` lights.
  void set_points(const std::vector<glm::vec3>& points, uint32_t light_count);
  // Surface points with their normals, looked up as the opaque pass does (normal
  // offset, soft-shadow kernels); results() as for points.
  void set_surface_points(const std::vector<glm::vec3>& points, const std::vector<glm::vec3>& normals,
                          uint32_t light_count);
  // Switches this pass to texel curves: the samples are uploaded now. Texels must
  // lie inside their light's level-0 map and lights be the scene's (texels of a light's first map).
  void set_texel_samples(const std::vector<TexelSample>& samples);
  // A results buffer per frame in flight (passes/frame/frames_in_flight.h; 1 by default).
  void set_frames_in_flight(uint32_t count) { results_.set_frames(ctx_, count); }
  // Adds "shadow probes" (or "shadow texel curves") reading the maps; the results
  // are ready after the frame, in its slot (shadows.frame_slot). Probes ask paged maps
  // for the pages they read: shadows.page_requests moves on to the pass's write.
  void add_to_graph(rg::Graph& graph, ShadowInputs& shadows);
  // results()[light][point], after the frame recorded into `slot` completed (points mode).
  std::vector<std::vector<float>> results(uint32_t slot = 0) const;
  // One result per texel sample, in set_texel_samples() order (texel-curve mode).
  std::vector<TexelSampleResult> texel_results(uint32_t slot = 0) const;

 private:
  enum class Mode : uint32_t {
    points = shared::kProbePoints,
    texel_curves = shared::kProbeTexelCurves,
    surface_points = shared::kProbeSurfacePoints,
  };
  void upload_points(std::vector<glm::vec4> packed, uint32_t count, uint32_t light_count, Mode mode);
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Buffer points_;
  FrameBuffers results_;
  uint32_t point_count_ = 0, light_count_ = 0;
  Mode mode_ = Mode::points;
};

}  // namespace avsm::passes
