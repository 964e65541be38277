// Deep shadow maps (Lokovic & Veach 2000): per texel the exact curve of its whole
// capture list, compressed greedily to an error bound, with a variable node count stored in a
// pool shared by the texels (dsm_build.comp; layout: shared/map_layouts.h).
// The pool starts at 8 nodes per texel and grows after a frame that needed more; the
// build is as many dispatches as the last frame's longest list needed (lavapipe ends a
// shader's loops after 65535 passes: see dsm_build.comp), one to start with.
#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>

#include "gpu/shader_compiler.h"
#include "passes/shadows/techniques/avsm/avsm_variants.h"
#include "passes/shadows/techniques/technique.h"
#include "shared/map_layouts.h"
#include "shared/passes/shadows/techniques/map_build.h"

namespace avsm::passes {
namespace {

constexpr TechniqueParameter kDsmParameters[] = {
    {"error", 0.01, 0, 1, 0, "the largest transmittance error the compression may make, in (0, 1)"},
};

uint64_t round_up(uint64_t value, uint64_t multiple) { return (value + multiple - 1) / multiple * multiple; }

class DsmBuilder final : public TechniqueBuilder {
 public:
  DsmBuilder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
      : ctx_(ctx), pipelines_(avsm_node_variants(ctx, shaders, "passes/shadows/techniques/dsm/dsm_build.comp", "dsm build", false)) {}
  rg::BufferHandle add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const override;

 private:
  gpu::Context& ctx_;
  gpu::ComputeVariants pipelines_;
};

class Dsm final : public ShadowTechnique {
 public:
  std::string_view name() const override { return "dsm"; }
  std::string_view summary() const override { return "deep shadow maps: exact curves compressed to an error bound"; }
  std::span<const TechniqueParameter> parameters() const override { return kDsmParameters; }
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
    state.build_dispatches = 1;
  }
  bool map_is_texel_ranges() const override { return false; }  // a header, then a node pool
  uint64_t map_bytes(const scene::ShadowSettings&, const TechniqueMapState& state) const override {
    return (uint64_t(shared::dsm_pool_base(state.layout.resolution)) + 2 * state.pool_nodes) * 4;
  }
  std::unique_ptr<TechniqueBuilder> create_builder(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) const override {
    return std::make_unique<DsmBuilder>(ctx, shaders);
  }
  // Counter word 1 holds the pool nodes the texels asked for; the map is replaced by a
  // larger one when they did not fit (the frame has completed, nothing reads it). Word
  // 2: the build dispatches the longest list needed, which the next frame makes.
  bool finish_frame(const uint32_t counters[3], TechniqueMapState& state, LightShadowStats& stats) const override {
    stats.dsm_pool = DsmPoolStats{counters[1], state.pool_nodes, counters[1] > state.pool_nodes,
                                  state.build_dispatches, counters[2], counters[2] > state.build_dispatches};
    if (stats.dsm_pool->build_cut_short) stats.grew = true;  // rendering again does better
    state.build_dispatches = std::max(counters[2], 1u);
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

// "<prefix> dsm build <k>": dispatch k of the build (dsm_build.comp). The texels' builds
// go on from dispatch to dispatch in the map (layout: shared/map_layouts.h), bound on
// their own as "Builds".
rg::BufferHandle DsmBuilder::add_to_graph(const TechniqueBuild& b, CaptureLists& lists) const {
  rg::BufferHandle map = add_clear_pass(b.graph, b.prefix, b.map);
  const uint32_t resolution = b.view.resolution;
  const uint64_t texels = uint64_t(resolution) * resolution;
  const uint64_t builds_offset = uint64_t(shared::dsm_builds_base(resolution)) * 4;
  const uint64_t builds_bytes = texels * shared::kDsmBuildWords * 4;
  for (uint32_t dispatch = 0; dispatch <= b.state.build_dispatches; ++dispatch) {
    struct Data {
      rg::TextureHandle heads;
      rg::BufferHandle nodes, map, counter;
    };
    const shared::MapBuildPush parameters{resolution, dispatch, b.view.near_depth, b.view.far_depth,
                                          float(dsm().error(b.settings))};
    const Data& data = b.graph.add_pass<Data>(b.prefix + " dsm build " + std::to_string(dispatch), rg::QueueType::Compute,
        [&](rg::PassBuilder& pb, Data& d) {
          d.heads = pb.read(lists.heads, rg::Usage::StorageRead);
          d.nodes = pb.read(lists.nodes, rg::Usage::StorageRead);
          d.map = pb.read_write(map, rg::Usage::StorageReadWrite);  // allocates from its own pool
          d.counter = pb.read_write(lists.counter, rg::Usage::StorageReadWrite);
        },
        [this, parameters, builds_offset, builds_bytes, &pipeline = pipelines_.get(0)](const Data& d,
                                                                                      rg::PassContext& c) {
          const gpu::BufferRange map_range = c.buffer(d.map);  // a region of the shadow map atlas
          pipeline.bind(c.cmd());
          gpu::Bindings(ctx_, pipeline)
              .image("capture_heads", c.view(d.heads), c.layout(d.heads))
              .buffer("CaptureNodes", c.buffer(d.nodes))
              .buffer("Map", map_range)
              .buffer("Counter", c.buffer(d.counter))
              .buffer("Builds", gpu::BufferRange(map_range.buffer, builds_bytes, map_range.offset + builds_offset))
              .push(c.cmd());
          pipeline.push_constants(c.cmd(), parameters);
          pipeline.dispatch_threads(c.cmd(), parameters.resolution, parameters.resolution);
        });
    map = data.map;
    lists.counter = data.counter;
  }
  return map;
}

}  // namespace

const ShadowTechnique& dsm_technique() { return dsm(); }

}  // namespace avsm::passes
