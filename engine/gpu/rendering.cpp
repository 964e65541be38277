#include "gpu/rendering.h"

#include <vector>

#include "gpu/barriers.h"
#include "gpu/resources.h"

namespace avsm::gpu {

void begin_rendering(VkCommandBuffer cmd, VkExtent2D extent, std::span<const ColorTarget> colors,
                     const DepthTarget* depth, bool flip_y) {
  std::vector<VkRenderingAttachmentInfo> color_infos;
  for (const ColorTarget& target : colors) {
    VkRenderingAttachmentInfo info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
    info.imageView = target.view;
    info.imageLayout = target.layout;
    info.loadOp = target.load ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    info.storeOp = VK_ATTACHMENT_STORE_OP_STORE;
    info.clearValue.color = target.clear;
    color_infos.push_back(info);
  }
  VkRenderingAttachmentInfo depth_info{VK_STRUCTURE_TYPE_RENDERING_ATTACHMENT_INFO};
  if (depth) {
    depth_info.imageView = depth->view;
    depth_info.imageLayout = depth->layout;
    depth_info.loadOp = depth->read_only ? VK_ATTACHMENT_LOAD_OP_LOAD : VK_ATTACHMENT_LOAD_OP_CLEAR;
    depth_info.storeOp = depth->read_only ? VK_ATTACHMENT_STORE_OP_NONE
                         : depth->store   ? VK_ATTACHMENT_STORE_OP_STORE
                                          : VK_ATTACHMENT_STORE_OP_DONT_CARE;
    depth_info.clearValue.depthStencil = {depth->clear, 0};
  }
  VkRenderingInfo rendering{VK_STRUCTURE_TYPE_RENDERING_INFO};
  rendering.renderArea = {{0, 0}, extent};
  rendering.layerCount = 1;
  rendering.colorAttachmentCount = uint32_t(color_infos.size());
  rendering.pColorAttachments = color_infos.data();
  rendering.pDepthAttachment = depth ? &depth_info : nullptr;
  vkCmdBeginRendering(cmd, &rendering);

  float width = float(extent.width), height = float(extent.height);
  VkViewport viewport = flip_y ? VkViewport{0, height, width, -height, 0, 1} : VkViewport{0, 0, width, height, 0, 1};
  VkRect2D scissor{{0, 0}, extent};
  vkCmdSetViewport(cmd, 0, 1, &viewport);
  vkCmdSetScissor(cmd, 0, 1, &scissor);
}

void clear_with_rendering(VkCommandBuffer cmd, const Image& target) {
  image_barrier(cmd, target.handle(), target.full_range(), VK_IMAGE_LAYOUT_UNDEFINED,
                VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, {}, kColorWrite);
  ColorTarget color{target.view()};
  begin_rendering(cmd, {target.desc().width, target.desc().height}, {&color, 1});
  vkCmdEndRendering(cmd);
}

}  // namespace avsm::gpu
