#include <rendergraph/vulkan/pass_context.h>

#include "gpu/resources.h"

namespace rg {

const PlannedAccess& PassContext::access(ResourceKind kind, uint32_t index, uint32_t graph_id) const {
  (void)graph_id;
  for (const PlannedAccess& a : pass_->accesses)
    if (a.resource == index && plan_.resources[index].kind == kind) return a;
  std::string resource = index < plan_.resources.size() ? plan_.resources[index].name : "#" + std::to_string(index);
  throw GraphError("pass '" + pass_->name + "': uses " + to_string(kind) + " '" + resource +
                   "' that its setup did not declare");
}

VkImage PassContext::image(TextureHandle texture) const {
  access(ResourceKind::Texture, texture.index, texture.graph_id);
  return images_[texture.index]->handle();
}

VkImageView PassContext::view(TextureHandle texture) const {
  access(ResourceKind::Texture, texture.index, texture.graph_id);
  return images_[texture.index]->view();
}

VkImageView PassContext::mip_view(TextureHandle texture, uint32_t level) const {
  access(ResourceKind::Texture, texture.index, texture.graph_id);
  return images_[texture.index]->mip_view(level);
}

VkImageLayout PassContext::layout(TextureHandle texture) const {
  return access(ResourceKind::Texture, texture.index, texture.graph_id).layout;
}

const TextureDesc& PassContext::desc(TextureHandle texture) const {
  access(ResourceKind::Texture, texture.index, texture.graph_id);
  return plan_.resources[texture.index].texture;
}

avsm::gpu::BufferRange PassContext::buffer(BufferHandle buffer) const {
  access(ResourceKind::Buffer, buffer.index, buffer.graph_id);
  return buffers_[buffer.index];
}

uint64_t PassContext::size(BufferHandle buffer) const {
  access(ResourceKind::Buffer, buffer.index, buffer.graph_id);
  return plan_.resources[buffer.index].buffer.size;
}

}  // namespace rg
