// Opacity shadow maps (Kim & Neumann 2001): K planes of accumulated optical depth over
// the light's caster depth range (shaders/passes/osm_build.comp, K floats per texel).
#include "gpu/shader_compiler.h"
#include "passes/map_build_pass.h"
#include "passes/techniques/technique.h"

namespace avsm::passes {
namespace {

constexpr TechniqueParameter kParameters[] = {
    {"slices", 32, 4, 64, 4, "opacity planes over the light's caster depth range"},
    {"depth_bias", 1, 0, 16, 0, "slices a receiver looks up in front of itself, against self-shadowing"},
};

class OsmBuilder final : public TechniqueBuilder {
 public:
  OsmBuilder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
      : build_(ctx, shaders, "shaders/passes/osm_build.comp", "osm build") {}
  rg::BufferHandle add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const override;

 private:
  MapBuildPass build_;
};

class Osm final : public ShadowTechnique {
 public:
  std::string_view name() const override { return "osm"; }
  std::string_view summary() const override { return "opacity shadow maps: optical depth at K planes"; }
  std::span<const TechniqueParameter> parameters() const override { return kParameters; }
  std::string label(const scene::ShadowSettings& s) const override { return "OSM-" + std::to_string(slices(s)); }
  uint64_t map_bytes(const scene::ShadowSettings& s, const TechniqueMapState& state) const override {
    return uint64_t(state.layout.resolution) * state.layout.resolution * slices(s) * 4;
  }
  // A surface's own blocker is smeared over a slice (1/K of the range): receivers
  // look up `depth_bias` slices in front of themselves.
  void fill(shared::GpuShadow& record, const scene::ShadowSettings& s, const LightView& view) const override {
    record.node_count = slices(s);
    const float slice = (view.far_depth - view.near_depth) / float(slices(s));
    record.depth_range.z = float(parameter(s, "depth_bias")) * slice;
  }
  std::unique_ptr<TechniqueBuilder> create_builder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) const override {
    return std::make_unique<OsmBuilder>(ctx, shaders);
  }
  uint32_t slices(const scene::ShadowSettings& s) const { return uint32_t(parameter(s, "slices")); }
};

const Osm& osm() {
  static const Osm technique;
  return technique;
}

rg::BufferHandle OsmBuilder::add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const {
  return build_.add_to_graph(b.graph, b.prefix, lists, b.map,
                             {b.view.resolution, osm().slices(b.settings), b.view.near_depth, b.view.far_depth, 0.0f});
}

}  // namespace

const ShadowTechnique& osm_technique() { return osm(); }

}  // namespace avsm::passes
