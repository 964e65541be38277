#include "passes/map_build_pass.h"

#include <rendergraph/vulkan/pass_context.h>

namespace avsm::passes {

static_assert(sizeof(MapBuildParameters) == 20, "mirrors the build shaders' push constants");

MapBuildPass::MapBuildPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const std::string& shader,
                           std::string name)
    : ctx_(ctx), pipeline_(gpu::Pipeline::compute(ctx, shaders.load(shader), name)), name_(std::move(name)) {}

rg::BufferHandle MapBuildPass::add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                            rg::BufferHandle map, const MapBuildParameters& parameters) const {
  struct Data {
    rg::TextureHandle heads;
    rg::BufferHandle nodes, map;
  };
  const Data& data = graph.add_pass<Data>(prefix + " " + name_, rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) {
        d.heads = b.read(lists.heads, rg::Usage::StorageRead);
        d.nodes = b.read(lists.nodes, rg::Usage::StorageRead);
        d.map = b.write(map, rg::Usage::StorageWrite);
      },
      [this, parameters](const Data& d, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings(ctx_, pipeline_)
            .image(0, c.view(d.heads), c.layout(d.heads))
            .buffer(1, c.buffer(d.nodes))
            .buffer(2, c.buffer(d.map))
            .push(c.cmd());
        pipeline_.push_constants(c.cmd(), parameters);
        pipeline_.dispatch_threads(c.cmd(), parameters.resolution, parameters.resolution);
      });
  return data.map;
}

}  // namespace avsm::passes
