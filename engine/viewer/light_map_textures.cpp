#include "viewer/light_map_textures.h"

#include <string>

#include "gpu/barriers.h"
#include "gpu/context.h"

namespace avsm::viewer {

namespace {

bool same_size(const gpu::Image& a, const gpu::Image& b) {
  return a.desc().width == b.desc().width && a.desc().height == b.desc().height && a.desc().format == b.desc().format;
}

// The panel samples the textures in fragment shaders.
constexpr gpu::Access kPanelRead{VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT};

}  // namespace

bool LightMapTextures::record_copies(VkCommandBuffer cmd, const std::vector<gpu::Image>& sources) {
  bool recreated = textures_.size() != sources.size();
  for (size_t i = 0; !recreated && i < sources.size(); ++i) recreated = !same_size(textures_[i], sources[i]);
  if (recreated) {
    textures_.clear();
    for (size_t i = 0; i < sources.size(); ++i) {
      gpu::ImageDesc desc = sources[i].desc();
      desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
      desc.name = "panel light map " + std::to_string(i);
      textures_.push_back(gpu::Image::create(ctx_, desc));
    }
  }
  for (size_t i = 0; i < sources.size(); ++i) {
    const gpu::Image& src = sources[i];
    gpu::Image& dst = textures_[i];
    // The previous contents are not needed; the panel's last reads must finish first.
    gpu::image_barrier(cmd, dst.handle(), dst.full_range(), VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, kPanelRead, gpu::kTransferWrite);
    VkImageCopy region{};
    region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    region.extent = {src.desc().width, src.desc().height, 1};
    vkCmdCopyImage(cmd, src.handle(), VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, dst.handle(),
                   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, 1, &region);
    gpu::image_barrier(cmd, dst.handle(), dst.full_range(), VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL,
                       VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, gpu::kTransferWrite, kPanelRead);
  }
  return recreated;
}

}  // namespace avsm::viewer
