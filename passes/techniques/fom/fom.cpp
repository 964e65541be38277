// Fourier opacity maps (Jansen & Bavoil 2010): the optical depth along the light's
// caster depth range as K Fourier terms (shaders/passes/fom_build.comp, K (a, b) pairs).
#include "gpu/shader_compiler.h"
#include "passes/map_build_pass.h"
#include "passes/techniques/technique.h"

namespace avsm::passes {
namespace {

constexpr TechniqueParameter kParameters[] = {
    {"terms", 16, 2, 32, 2, "Fourier terms of the optical depth"},
    {"depth_bias", 1, 0, 16, 0, "slices (range / K) a receiver looks up in front of itself, against self-shadowing"},
};

class FomBuilder final : public TechniqueBuilder {
 public:
  FomBuilder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
      : build_(ctx, shaders, "shaders/passes/fom_build.comp", "fom build") {}
  rg::BufferHandle add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const override;

 private:
  MapBuildPass build_;
};

class Fom final : public ShadowTechnique {
 public:
  std::string_view name() const override { return "fom"; }
  std::string_view summary() const override { return "Fourier opacity maps: optical depth as K Fourier terms"; }
  std::span<const TechniqueParameter> parameters() const override { return kParameters; }
  std::string label(const scene::ShadowSettings& s) const override { return "FOM-" + std::to_string(terms(s)); }
  uint64_t map_bytes(const scene::ShadowSettings& s, const TechniqueMapState& state) const override {
    return uint64_t(state.layout.resolution) * state.layout.resolution * terms(s) * 8;
  }
  // As for opacity maps: a surface's own blocker is smeared over range / K.
  void fill(shared::GpuShadow& record, const scene::ShadowSettings& s, const LightView& view) const override {
    record.node_count = terms(s);
    const float slice = (view.far_depth - view.near_depth) / float(terms(s));
    record.depth_range.z = float(parameter(s, "depth_bias")) * slice;
  }
  std::unique_ptr<TechniqueBuilder> create_builder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) const override {
    return std::make_unique<FomBuilder>(ctx, shaders);
  }
  uint32_t terms(const scene::ShadowSettings& s) const { return uint32_t(parameter(s, "terms")); }
};

const Fom& fom() {
  static const Fom technique;
  return technique;
}

rg::BufferHandle FomBuilder::add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const {
  return build_.add_to_graph(b.graph, b.prefix, lists, b.map,
                             {b.view.resolution, fom().terms(b.settings), b.view.near_depth, b.view.far_depth, 0.0f});
}

}  // namespace

const ShadowTechnique& fom_technique() { return fom(); }

}  // namespace avsm::passes
