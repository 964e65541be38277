#pragma once
// Hair strands from the camera as camera-facing ribbons, alpha-blended with depth
// test (no depth write) over the colour that the smoke was already composited into.
// A ribbon narrower than a pixel is widened to one pixel and its opacity scaled
// down by the same factor, so thin strands keep their coverage instead of
// flickering. Strands are not sorted: with low per-strand opacity the
// order-dependence is small. The shading (Kajiya-Kay diffuse, attenuated by the
// lights' transmittance maps, self-shadowing included) and the smoke in front of
// the strand come per vertex from HairLightingPass; the reference path evaluates
// the shading per fragment instead. A fragment adds a * (S + T * colour) over
// (1 - a) * colour, S and T being the smoke between the camera and the strand, so
// hair in front of smoke is not darkened by the smoke behind it.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "gpu/resources.h"
#include "passes/shadows/shadow_casters.h"
#include "passes/shadows/shadow_maps_fwd.h"
#include "passes/frame/view.h"
#include "scene/scene.h"

namespace avsm::passes {

struct FrameInputs;  // passes/frame/frame_inputs.h

class HairPass {
 public:
  HairPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  void set_scene(const scene::Scene& scene);
  uint32_t segment_count() const { return segment_count_; }
  uint32_t point_count() const { return point_count_; }
  // Per strand vertex, the unit tangent along its strand (vec4), read by HairLightingPass.
  const gpu::Buffer& tangents() const { return tangents_; }
  // Strand vertices (vec4), read by the hair quality pass.
  const gpu::Buffer& points() const { return points_; }
  // The strands as shadow casters (passes/shadows/capture/capture_hair_pass.h).
  StrandCasters casters() const {
    return {points_.handle(),  points_.size(),  segments_.handle(), segments_.size(),
            strands_.handle(), strands_.size(), segment_count_};
  }

  // Draws onto `color` (loaded), testing against `depth`; returns the new colour version.
  // `vertex_lights`: this frame's HairLightingPass output. `light_per_fragment`: the
  // reference shading, with shadow lookups per fragment.
  rg::TextureHandle add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                 rg::BufferHandle vertex_lights, bool light_per_fragment, FrameInputs& frame);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline lit_per_vertex_, lit_per_fragment_;  // hair.frag, hair_reference.frag
  gpu::Buffer points_, tangents_, segments_, strands_;
  uint32_t segment_count_ = 0;
  uint32_t point_count_ = 0;
};

}  // namespace avsm::passes
