#include "passes/map_build_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "passes/avsm_variants.h"

namespace avsm::passes {

MapBuildPass::MapBuildPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const std::string& shader,
                           std::string name, bool per_node_count)
    : ctx_(ctx),
      per_node_count_(per_node_count),
      pipelines_(avsm_node_variants(ctx, shaders, shader, name, per_node_count)),
      name_(std::move(name)) {}

rg::BufferHandle MapBuildPass::add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                            rg::BufferHandle map, const MapBuildParameters& parameters,
                                            rg::BufferHandle* counter) const {
  struct Data {
    rg::TextureHandle heads;
    rg::BufferHandle nodes, map, counter;
  };
  const Data& data = graph.add_pass<Data>(prefix + " " + name_, rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) {
        d.heads = b.read(lists.heads, rg::Usage::StorageRead);
        d.nodes = b.read(lists.nodes, rg::Usage::StorageRead);
        // The deep shadow map allocates from a pool inside the map: it reads its own writes.
        d.map = counter ? b.read_write(map, rg::Usage::StorageReadWrite) : b.write(map, rg::Usage::StorageWrite);
        if (counter) d.counter = b.read_write(*counter, rg::Usage::StorageReadWrite);
      },
      [this, parameters, &pipeline = pipelines_.get(per_node_count_ ? parameters.count : 0)](
          const Data& d, rg::PassContext& c) {
        pipeline.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline);
        bindings.image("capture_heads", c.view(d.heads), c.layout(d.heads))
            .buffer("CaptureNodes", c.buffer(d.nodes))
            .buffer("Map", c.buffer(d.map));
        if (d.counter.valid()) bindings.buffer("Counter", c.buffer(d.counter));
        bindings.push(c.cmd());
        pipeline.push_constants(c.cmd(), parameters);
        pipeline.dispatch_threads(c.cmd(), parameters.resolution, parameters.resolution);
      });
  if (counter) *counter = data.counter;
  return data.map;
}

}  // namespace avsm::passes
