#include "passes/techniques/opacity_map_technique.h"

#include <string>

#include "gpu/shader_compiler.h"
#include "passes/map_build_pass.h"

namespace avsm::passes {
namespace {

class OpacityMapBuilder final : public TechniqueBuilder {
 public:
  OpacityMapBuilder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const OpacityMapTechnique& technique,
                    std::string_view shader, std::string_view pass)
      : technique_(technique), build_(ctx, shaders, std::string(shader), std::string(pass)) {}
  rg::BufferHandle add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const override {
    return build_.add_to_graph(b.graph, b.prefix, lists, b.map,
                               {b.view.resolution, technique_.size(b.settings), b.view.near_depth, b.view.far_depth, 0.0f});
  }

 private:
  const OpacityMapTechnique& technique_;
  MapBuildPass build_;
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
  return std::make_unique<OpacityMapBuilder>(ctx, shaders, *this, spec_.build_shader, spec_.build_pass);
}

}  // namespace avsm::passes
