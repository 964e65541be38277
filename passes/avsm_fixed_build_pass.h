#pragma once
// The fixed-memory AVSM build: a light's map straight from its casters, without
// per-fragment lists (shaders/common/avsm_fixed_build.glsl). Per 8x8 tile, each
// texel's curve starts with the nearest opaque caster (LightDepthPass), takes every
// hair crossing in segment order (HairBinsPass) and the smoke along its ray, and is
// written to level 0 of the map. Memory: the map, the depth image and the hair bins,
// whatever the depth complexity. Shaders: avsm_fixed_build.comp (density atlas) and
// avsm_fixed_build_nanovdb.comp, per node count.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/avsm_map_layout.h"
#include "passes/hair_bins_pass.h"
#include "passes/light_depth_pass.h"
#include "passes/light_view.h"
#include "passes/shadow_casters.h"

namespace avsm::passes {

struct FixedBuildInputs {
  rg::TextureHandle depth;  // LightDepthPass
  HairBins bins;            // HairBinsPass
};

class AvsmFixedBuildPass {
 public:
  AvsmFixedBuildPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Declares the light depth and hair bins passes and "<prefix> avsm fixed build",
  // which writes level 0 of `map` (layout.bytes() at least). `counter` (16 bytes, host
  // readable) gets the kFixedCounter* words. Returns the map's new version.
  rg::BufferHandle add_to_graph(rg::Graph& graph, const std::string& prefix, rg::BufferHandle map,
                                rg::BufferHandle counter, const AvsmMapLayout& layout, const LightView& light,
                                const ShadowCasters& casters, uint32_t smoke_samples_per_segment) const;

 private:
  gpu::Context& ctx_;
  LightDepthPass depth_;
  HairBinsPass bins_;
  gpu::ComputeVariants from_atlas_, from_nanovdb_;  // per node count
  gpu::Sampler depth_sampler_;
  gpu::Buffer placeholder_;  // bound for casters a frame does not have
};

}  // namespace avsm::passes
