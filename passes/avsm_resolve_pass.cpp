#include "passes/avsm_resolve_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <stdexcept>
#include <string>

namespace avsm::passes {
namespace {

// Mirrors shaders/passes/avsm_resolve.comp.
struct Push {
  uint32_t resolution;
  uint32_t node_count;
  float far_depth;
};

}  // namespace

AvsmResolvePass::AvsmResolvePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx), pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/avsm_resolve.comp"), "avsm resolve")) {}

rg::BufferHandle AvsmResolvePass::add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                               rg::BufferHandle map, const AvsmMapLayout& layout, float far_depth) const {
  if (layout.nodes < 4 || layout.nodes > 16 || layout.nodes % 4 != 0)
    throw std::invalid_argument("AvsmResolvePass: " + std::to_string(layout.nodes) + " nodes; use 4, 8, 12 or 16");
  struct Data {
    rg::TextureHandle heads;
    rg::BufferHandle nodes, map;
  };
  const Data& data = graph.add_pass<Data>(prefix + " avsm resolve", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) {
        d.heads = b.read(lists.heads, rg::Usage::StorageRead);
        d.nodes = b.read(lists.nodes, rg::Usage::StorageRead);
        d.map = b.write(map, rg::Usage::StorageWrite);
      },
      [this, layout, far_depth](const Data& d, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings(ctx_, pipeline_)
            .image(0, c.view(d.heads), c.layout(d.heads))
            .buffer(1, c.buffer(d.nodes))
            .buffer(2, c.buffer(d.map))
            .push(c.cmd());
        pipeline_.push_constants(c.cmd(), Push{layout.resolution, layout.nodes, far_depth});
        pipeline_.dispatch_threads(c.cmd(), layout.resolution, layout.resolution);
      });
  return data.map;
}

}  // namespace avsm::passes
