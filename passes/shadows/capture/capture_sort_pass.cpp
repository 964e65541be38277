#include "passes/shadows/capture/capture_sort_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "shared/passes/shadows/capture/capture_sort.h"

namespace avsm::passes {

CaptureSortPass::CaptureSortPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx), pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/shadows/capture/capture_sort.comp"), "capture sort")) {}

CaptureLists CaptureSortPass::add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                           uint32_t resolution) const {
  return graph.add_pass<CaptureLists>(prefix + " sort lists", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, CaptureLists& d) {
        d = lists;
        d.heads = b.read_write(lists.heads, rg::Usage::StorageReadWrite);
        d.nodes = b.read_write(lists.nodes, rg::Usage::StorageReadWrite);
      },
      [this, resolution](const CaptureLists& d, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings(ctx_, pipeline_)
            .image("capture_heads", c.view(d.heads), c.layout(d.heads))
            .buffer("CaptureNodes", c.buffer(d.nodes))
            .push(c.cmd());
        pipeline_.push_constants(c.cmd(), shared::CaptureSortPush{resolution});
        pipeline_.dispatch_threads(c.cmd(), resolution, resolution);
      });
}

}  // namespace avsm::passes
