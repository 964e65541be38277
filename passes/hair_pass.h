#pragma once
// Hair strands from the camera as camera-facing ribbons, alpha-blended over the
// opaque colour with depth test (no depth write). A ribbon narrower than a
// pixel is widened to one pixel and its opacity scaled down by the same factor,
// so thin strands keep their coverage instead of flickering. Strands are not
// sorted: with low per-strand opacity the order-dependence is small, and the
// shading term (Kajiya-Kay diffuse) is attenuated by the light's transmittance
// map (self-shadowing included: the strands cast into it).
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "gpu/resources.h"
#include "passes/shadow_casters.h"
#include "passes/shadow_maps_fwd.h"
#include "passes/view.h"
#include "scene/scene.h"

namespace avsm::passes {

class HairPass {
 public:
  HairPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  void set_scene(const scene::Scene& scene);
  uint32_t segment_count() const { return segment_count_; }
  // Strand vertices (vec4), read by the hair quality pass.
  const gpu::Buffer& points() const { return points_; }
  // The strands as shadow casters (passes/capture_hair_pass.h).
  StrandCasters casters() const { return {points_.handle(), segments_.handle(), strands_.handle(), segment_count_}; }

  // Draws onto `color` (loaded), testing against `depth`; returns the new colour version.
  rg::TextureHandle add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth, const View& view,
                                 const gpu::Buffer& lights, uint32_t light_count, const ShadowInputs& shadows);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Buffer points_, segments_, strands_;
  uint32_t segment_count_ = 0;
};

}  // namespace avsm::passes
