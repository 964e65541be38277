#include "passes/shadows/capture/capture_lists.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/pipeline.h"
#include "passes/shadows/light_view.h"

namespace avsm::passes {

CaptureLists add_capture_clear_pass(rg::Graph& graph, const std::string& prefix, uint32_t resolution,
                                    uint64_t node_capacity, rg::BufferHandle counter) {
  const CaptureLists& lists = graph.add_pass<CaptureLists>(prefix + " clear lists", rg::QueueType::Graphics,
      [&](rg::PassBuilder& b, CaptureLists& d) {
        const rg::TextureDesc heads{resolution, resolution, 1, 1, 1, kCaptureHeadFormat, kShadowResolutionSetting};
        d.heads = b.write(b.create_texture(prefix + " list heads", heads), rg::Usage::TransferDst);
        // Only the first node is cleared: appends overwrite nodes whole, and the
        // graph must see the buffer written before the captures read-modify it.
        const rg::BufferDesc nodes{node_capacity * kCaptureSegmentBytes, kShadowResolutionSetting};
        d.nodes = b.write(b.create_buffer(prefix + " list nodes", nodes), rg::Usage::TransferDst);
        d.counter = b.write(counter, rg::Usage::TransferDst);
      },
      [](const CaptureLists& d, rg::PassContext& c) {
        const VkClearColorValue end_of_list{.uint32 = {~0u, 0, 0, 0}};
        const VkImageSubresourceRange all{VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1};
        vkCmdClearColorImage(c.cmd(), c.image(d.heads), c.layout(d.heads), &end_of_list, 1, &all);
        vkCmdFillBuffer(c.cmd(), c.buffer(d.nodes), 0, kCaptureSegmentBytes, ~0u);
        vkCmdFillBuffer(c.cmd(), c.buffer(d.counter), 0, VK_WHOLE_SIZE, 0);
      });
  return lists;
}

CaptureLists append_to_lists(rg::PassBuilder& builder, const CaptureLists& lists) {
  return {builder.read_write(lists.heads, rg::Usage::StorageReadWrite),
          builder.read_write(lists.nodes, rg::Usage::StorageReadWrite),
          builder.read_write(lists.counter, rg::Usage::StorageReadWrite)};
}

void bind_capture_lists(gpu::Bindings& bindings, const rg::PassContext& context, const CaptureLists& lists) {
  bindings.image("capture_heads", context.view(lists.heads), context.layout(lists.heads))
      .buffer("CaptureNodes", context.buffer(lists.nodes))
      .buffer("CaptureCounter", {context.buffer(lists.counter).buffer, sizeof(uint32_t), context.buffer(lists.counter).offset});
}

}  // namespace avsm::passes
