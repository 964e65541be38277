#include "passes/shadows/techniques/opacity_map_technique.h"

#include <string>

#include "gpu/shader_compiler.h"
#include "passes/shadows/fixed_build/fixed_build_pass.h"
#include "passes/shadows/techniques/map_build_pass.h"

namespace avsm::passes {
namespace {

class OpacityMapBuilder final : public TechniqueBuilder {
 public:
  OpacityMapBuilder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const OpacityMapTechnique& technique,
                    const OpacityMapTechnique::Spec& spec)
      : technique_(technique),
        build_(ctx, shaders, std::string(spec.build_shader), std::string(spec.build_pass)),
        fixed_(ctx, shaders, std::string(spec.fixed_build_shader), std::string(spec.fixed_build_pass),
               /*per_node_count=*/false) {}
  rg::BufferHandle add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const override {
    return build_.add_to_graph(b.graph, b.prefix, lists, b.map,
                               {b.view.resolution, technique_.size(b.settings), b.view.near_depth, b.view.far_depth, 0.0f});
  }
  rg::BufferHandle add_fixed_to_graph(const FixedTechniqueBuild& b) const override {
    return fixed_.add_to_graph(b.graph, b.prefix, {b.map, b.counter, technique_.size(b.settings)}, b.view, b.casters,
                               b.smoke_samples_per_segment);
  }

 private:
  const OpacityMapTechnique& technique_;
  MapBuildPass build_;
  FixedBuildPass fixed_;
};

}  // namespace

std::string OpacityMapTechnique::label(const scene::ShadowSettings& s) const {
  return std::string(spec_.label_prefix) + std::to_string(size(s));
}

uint64_t OpacityMapTechnique::map_bytes(const scene::ShadowSettings& s, const TechniqueMapState& state) const {
  return uint64_t(state.layout.resolution) * state.layout.resolution * size(s) * spec_.bytes_per_size;
}

void OpacityMapTechnique::fill(shared::GpuShadow& record, const scene::ShadowSettings& s, const LightView& view) const {
  record.node_count = size(s);
  const float slice = (view.far_depth - view.near_depth) / float(size(s));
  record.depth_range.z = float(parameter(s, "depth_bias")) * slice;
}

std::unique_ptr<TechniqueBuilder> OpacityMapTechnique::create_builder(gpu::Context& ctx,
                                                                      const gpu::ShaderLibrary& shaders) const {
  return std::make_unique<OpacityMapBuilder>(ctx, shaders, *this, spec_);
}

}  // namespace avsm::passes
