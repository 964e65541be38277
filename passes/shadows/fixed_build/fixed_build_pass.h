#pragma once
// A light's map built straight from its casters, without per-fragment lists
// (shaders/common/fixed_build.glsl; scene::ShadowBuild::fixed). Per 8x8 tile, each
// texel starts with the nearest opaque caster (LightDepthPass), takes every hair
// crossing in segment order (HairBinsPass) and the smoke along its ray, and is written
// to level 0 of the map. Memory: the map, the depth image and the hair bins, whatever
// the depth complexity. Each technique that builds this way has its shader (AVSM:
// passes/shadows/techniques/avsm/avsm_fixed_build.comp, per node count; OSM and FOM in their folders)
// saying what a texel keeps of the segments.
#include <rendergraph/graph.h>

#include <optional>
#include <string>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/fixed_build/hair_bins_pass.h"
#include "passes/shadows/fixed_build/light_depth_pass.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_casters.h"
#include "passes/frame/volume_density_atlas.h"

namespace avsm::passes {

struct FixedBuildInputs {
  rg::TextureHandle depth;  // LightDepthPass
  HairBins bins;            // HairBinsPass
};

struct FixedBuildTarget {
  rg::BufferHandle map;      // written at level 0
  rg::BufferHandle counter;  // 16 bytes, host readable: the kFixedCounter* words
  uint32_t technique_size = 0;  // AVSM nodes, OSM planes, FOM terms
};

class FixedBuildPass {
 public:
  // `shader`: the technique's build; with `per_node_count` it is built per AVSM node
  // count (passes/shadows/techniques/avsm/avsm_variants.h) and technique_size picks the variant. `name`: the
  // pass name after the light prefix.
  FixedBuildPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const std::string& shader, std::string name,
                 bool per_node_count);
  // Declares the light depth and hair bins passes and "<prefix> <name>". Throws
  // std::invalid_argument for volumes without a density atlas. Returns the map's new version.
  rg::BufferHandle add_to_graph(rg::Graph& graph, const std::string& prefix, const FixedBuildTarget& target,
                                const LightView& light, const ShadowCasters& casters,
                                uint32_t smoke_samples_per_segment) const;

 private:
  gpu::Context& ctx_;
  std::string name_;
  bool per_node_count_;
  LightDepthPass depth_;
  HairBinsPass bins_;
  gpu::ComputeVariants pipelines_;  // per node count, or one (value 0)
  gpu::Sampler depth_sampler_;
  gpu::Buffer placeholder_;           // bound for casters a frame does not have
  VolumeDensityAtlas empty_atlas_;    // (one texel) likewise
};

}  // namespace avsm::passes
