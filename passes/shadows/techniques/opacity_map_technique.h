#pragma once
// What opacity shadow maps (osm/) and Fourier opacity maps (fom/) share: a map of K
// values per texel over the light's caster depth range, built by one pass over the
// capture lists (passes/shadows/techniques/map_build_pass.h), looked up `depth_bias` slices (range / K)
// in front of the receiver, since a surface's own blocker is smeared over a slice.
#include <string_view>

#include "passes/shadows/techniques/technique.h"

namespace avsm::passes {

class OpacityMapTechnique final : public ShadowTechnique {
 public:
  struct Spec {
    std::string_view name, summary;
    std::string_view label_prefix;    // "OSM-"
    std::string_view size_parameter;  // K: "slices", "terms"
    uint32_t bytes_per_size;          // map bytes per texel and unit of K
    std::string_view build_shader, build_pass;              // from the capture lists
    std::string_view fixed_build_shader, fixed_build_pass;  // straight from the casters
    std::span<const TechniqueParameter> parameters;  // with size_parameter and depth_bias
  };
  explicit OpacityMapTechnique(const Spec& spec) : spec_(spec) {}

  std::string_view name() const override { return spec_.name; }
  std::string_view summary() const override { return spec_.summary; }
  std::span<const TechniqueParameter> parameters() const override { return spec_.parameters; }
  std::string label(const scene::ShadowSettings& s) const override;
  uint64_t map_bytes(const scene::ShadowSettings& s, const TechniqueMapState& state) const override;
  void fill(shared::GpuShadow& record, const scene::ShadowSettings& s, const LightView& view) const override;
  std::unique_ptr<TechniqueBuilder> create_builder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) const override;
  // Additive by nature: built straight from the casters as their papers build them.
  bool builds_fixed() const override { return true; }

  uint32_t size(const scene::ShadowSettings& s) const { return uint32_t(parameter(s, spec_.size_parameter)); }

 private:
  Spec spec_;
};

}  // namespace avsm::passes
