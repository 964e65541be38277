#include "passes/shadows/techniques/map_build_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "passes/shadows/techniques/avsm/avsm_variants.h"

namespace avsm::passes {

MapBuildPass::MapBuildPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const std::string& shader,
                           std::string name, bool per_node_count)
    : ctx_(ctx),
      per_node_count_(per_node_count),
      pipelines_(avsm_node_variants(ctx, shaders, shader, name, per_node_count)),
      name_(std::move(name)) {}

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
      [this, parameters, &pipeline = pipelines_.get(per_node_count_ ? parameters.count : 0)](
          const Data& d, rg::PassContext& c) {
        pipeline.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline);
        bindings.image("capture_heads", c.view(d.heads), c.layout(d.heads))
            .buffer("CaptureNodes", c.buffer(d.nodes))
            .buffer("Map", c.buffer(d.map));
        bindings.push(c.cmd());
        pipeline.push_constants(c.cmd(), parameters);
        pipeline.dispatch_threads(c.cmd(), parameters.resolution, parameters.resolution);
      });
  return data.map;
}

}  // namespace avsm::passes
