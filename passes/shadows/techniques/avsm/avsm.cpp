// Adaptive volumetric shadow maps (Salvi et al., EGSR 2010): per texel a curve of N
// nodes of 4 bytes each (16-bit depth and transmittance: shaders/shared/map_layouts.h),
// built by streaming insertion and compression (passes/shadows/techniques/avsm/avsm_resolve_pass.h), with an
// optional mip chain for trilinear lookups (passes/shadows/techniques/avsm/avsm_mips_pass.h).
#include "gpu/shader_compiler.h"
#include "passes/shadows/fixed_build/fixed_build_pass.h"
#include "passes/shadows/techniques/avsm/avsm_mips_pass.h"
#include "passes/shadows/techniques/avsm/avsm_resolve_pass.h"
#include "passes/shadows/techniques/technique.h"

namespace avsm::passes {
namespace {

class AvsmBuilder final : public TechniqueBuilder {
 public:
  AvsmBuilder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
      : resolve_(ctx, shaders),
        fixed_(ctx, shaders, "passes/shadows/techniques/avsm/avsm_fixed_build.comp", "avsm fixed build", /*per_node_count=*/true),
        mips_(ctx, shaders) {}
  rg::BufferHandle add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const override {
    rg::BufferHandle map =
        resolve_.add_to_graph(b.graph, b.prefix, lists, b.map, b.state.layout, b.view.near_depth, b.view.far_depth);
    return mips_.add_to_graph(b.graph, b.prefix, map, b.state.layout, b.view.near_depth, b.view.far_depth);
  }
  rg::BufferHandle add_fixed_to_graph(const FixedTechniqueBuild& b) const override {
    rg::BufferHandle map = fixed_.add_to_graph(b.graph, b.prefix, {b.map, b.counter, b.state.layout.nodes}, b.view,
                                               b.casters, b.smoke_samples_per_segment);
    return mips_.add_to_graph(b.graph, b.prefix, map, b.state.layout, b.view.near_depth, b.view.far_depth);
  }

 private:
  AvsmResolvePass resolve_;
  FixedBuildPass fixed_;
  AvsmMipsPass mips_;
};

class Avsm final : public ShadowTechnique {
 public:
  std::string_view name() const override { return "avsm"; }
  std::string_view summary() const override { return "adaptive volumetric shadow maps, N nodes per texel (--nodes)"; }
  std::string label(const scene::ShadowSettings& s) const override { return "AVSM-" + std::to_string(s.nodes); }
  bool stores_avsm_nodes() const override { return true; }
  bool builds_fixed() const override { return true; }
  uint32_t mip_levels(const scene::ShadowSettings& s, uint32_t resolution) const override {
    return s.filter == scene::ShadowFilter::trilinear ? AvsmMapLayout::full_mip_count(resolution) : 1;
  }
  uint64_t map_bytes(const scene::ShadowSettings&, const TechniqueMapState& state) const override {
    return state.layout.bytes();
  }
  void fill(shared::GpuShadow& record, const scene::ShadowSettings& s, const LightView&) const override {
    record.node_count = uint32_t(s.nodes);
  }
  std::unique_ptr<TechniqueBuilder> create_builder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) const override {
    return std::make_unique<AvsmBuilder>(ctx, shaders);
  }
};

}  // namespace

const ShadowTechnique& avsm_technique() {
  static const Avsm technique;
  return technique;
}

}  // namespace avsm::passes
