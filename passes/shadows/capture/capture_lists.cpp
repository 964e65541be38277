#include "passes/shadows/capture/capture_lists.h"

#include "gpu/rendering.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/pipeline.h"
#include "passes/shadows/light_view.h"

namespace avsm::passes {

void begin_light_rendering(VkCommandBuffer cmd, const LightView& view) {
  // No attachments, so the render area may be any window of the raster: the viewport
  // and every vertex's framebuffer position are the whole raster's, bit for bit.
  const VkRect2D window{{int32_t(view.raster_origin.x), int32_t(view.raster_origin.y)}, {view.resolution, view.resolution}};
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = window;
  rendering.layerCount = 1;
  vkCmdBeginRendering(cmd, &rendering);
  const float raster = float(view.raster());
  const VkViewport viewport{0.0f, 0.0f, raster, raster, 0.0f, 1.0f};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &window);
}

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
        // At each range's own offset: a paged map's page builds count into regions of one buffer.
        const gpu::BufferRange nodes = c.buffer(d.nodes), counter = c.buffer(d.counter);
        vkCmdFillBuffer(c.cmd(), nodes, nodes.offset, kCaptureSegmentBytes, ~0u);
        vkCmdFillBuffer(c.cmd(), counter, counter.offset, counter.size, 0);
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
