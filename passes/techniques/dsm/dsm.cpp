// Deep shadow maps (Lokovic & Veach 2000): per texel the exact curve of its capture
// list, compressed greedily to an error bound, with a variable node count stored in a
// pool shared by the texels (dsm_build.comp; layout: shared/map_layouts.h).
// The pool starts at 8 nodes per texel and grows after a frame that needed more.
#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>

#include "gpu/shader_compiler.h"
#include "passes/map_build_pass.h"
#include "passes/techniques/technique.h"
#include "shared/map_layouts.h"

namespace avsm::passes {
namespace {

// The exact-curve nodes kept before compression (the build's curve capacity).
constexpr uint32_t kInputNodes = 16;

constexpr TechniqueParameter kParameters[] = {
    {"error", 0.01, 0, 1, 0, "the largest transmittance error the compression may make, in (0, 1)"},
};

uint64_t round_up(uint64_t value, uint64_t multiple) { return (value + multiple - 1) / multiple * multiple; }

class DsmBuilder final : public TechniqueBuilder {
 public:
  DsmBuilder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
      : build_(ctx, shaders, "passes/techniques/dsm/dsm_build.comp", "dsm build") {}
  rg::BufferHandle add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const override;

 private:
  MapBuildPass build_;
};

class Dsm final : public ShadowTechnique {
 public:
  std::string_view name() const override { return "dsm"; }
  std::string_view summary() const override { return "deep shadow maps: exact curves compressed to an error bound"; }
  std::span<const TechniqueParameter> parameters() const override { return kParameters; }
  void check(const scene::ShadowSettings& s, const std::string& who) const override {
    const double e = error(s);
    if (!(e > 0.0 && e < 1.0))
      throw std::invalid_argument(who + ": dsm parameter error = " + std::to_string(e) + "; use a value in (0, 1)");
  }
  std::string label(const scene::ShadowSettings& s) const override {
    char text[64];
    std::snprintf(text, sizeof(text), "DSM (error %g)", error(s));
    return text;
  }
  void prepare(TechniqueMapState& state) const override {
    state.pool_nodes = uint64_t(state.layout.resolution) * state.layout.resolution * 8;
  }
  uint64_t map_bytes(const scene::ShadowSettings&, const TechniqueMapState& state) const override {
    return (uint64_t(shared::dsm_pool_base(state.layout.resolution)) + 2 * state.pool_nodes) * 4;
  }
  void fill(shared::GpuShadow& record, const scene::ShadowSettings&, const LightView&) const override {
    record.node_count = kInputNodes;
  }
  std::unique_ptr<TechniqueBuilder> create_builder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) const override {
    return std::make_unique<DsmBuilder>(ctx, shaders);
  }
  // Counter word 1 holds the pool nodes the texels asked for; the map is replaced by a
  // larger one when they did not fit (the frame has completed, nothing reads it).
  bool finish_frame(const uint32_t counters[2], TechniqueMapState& state, LightShadowStats& stats) const override {
    stats.dsm_pool = DsmPoolStats{counters[1], state.pool_nodes, counters[1] > state.pool_nodes};
    if (!stats.dsm_pool->overflowed) return false;
    state.pool_nodes = round_up(counters[1] + counters[1] / 4, 1024);
    return true;
  }
  double error(const scene::ShadowSettings& s) const { return parameter(s, "error"); }
};

const Dsm& dsm() {
  static const Dsm technique;
  return technique;
}

// "<prefix> dsm clear" zeroes the pool counter (map word 0) before the build allocates from it.
rg::BufferHandle add_clear_pass(rg::Graph& graph, const std::string& prefix, rg::BufferHandle map) {
  struct Data {
    rg::BufferHandle map;
  };
  return graph.add_pass<Data>(prefix + " dsm clear", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) { d.map = b.write(map, rg::Usage::TransferDst); },
      [](const Data& d, rg::PassContext& c) {
        const gpu::BufferRange map = c.buffer(d.map);  // a region of the shadow map atlas
        vkCmdFillBuffer(c.cmd(), map, map.offset, 16, 0);
      })
      .map;
}

rg::BufferHandle DsmBuilder::add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const {
  rg::BufferHandle map = add_clear_pass(b.graph, b.prefix, b.map);
  return build_.add_to_graph(b.graph, b.prefix, lists, map,
                             {b.view.resolution, kInputNodes, b.view.near_depth, b.view.far_depth,
                              float(dsm().error(b.settings))},
                             &lists.counter);
}

}  // namespace

const ShadowTechnique& dsm_technique() { return dsm(); }

}  // namespace avsm::passes
