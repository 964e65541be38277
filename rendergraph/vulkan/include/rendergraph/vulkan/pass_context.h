#pragma once
// What a pass's execute callback receives from the Vulkan executor: the command
// buffer to record into and the physical resources behind the handles it declared.
// Defines the rg::PassContext that the planning core only forward-declares. The
// executor makes one per pass; so does the shadow pass list's record function
// (passes/shadows/shadow_pass_list.h), which runs a pass on resources a host's graph resolved.
#include <rendergraph/graph.h>
#include <vulkan/vulkan.h>

#include <vector>

#include "gpu/resources.h"

namespace avsm::gpu {
class Context;
}  // namespace avsm::gpu

namespace rg {

class PassContext {
 public:
  VkCommandBuffer cmd() const { return cmd_; }
  const avsm::gpu::Context& gpu() const { return gpu_; }
  const std::string& pass_name() const { return pass_->name; }

  // Only handles this pass declared in its setup resolve; anything else is a
  // GraphError naming the pass and the resource.
  VkImage image(TextureHandle texture) const;
  VkImageView view(TextureHandle texture) const;  // all mips and layers
  VkImageView mip_view(TextureHandle texture, uint32_t level) const;
  // The layout the plan put the texture in for this pass.
  VkImageLayout layout(TextureHandle texture) const;
  const TextureDesc& desc(TextureHandle texture) const;
  // The whole buffer (its handle and size); converts to VkBuffer.
  avsm::gpu::BufferRange buffer(BufferHandle buffer) const;
  uint64_t size(BufferHandle buffer) const;

  // `pass` of `plan` (its accesses give the layouts; `plan.resources` the names and
  // descriptions), its resources by plan resource index: `images` for textures, `buffers`
  // (each the bytes it occupies, with an explicit size) for buffers. Everything is
  // referenced, not copied: it must outlive the context.
  PassContext(const avsm::gpu::Context& gpu, VkCommandBuffer cmd, const PlannedPass& pass,
              const CompiledPlan& plan, const std::vector<const avsm::gpu::Image*>& images,
              const std::vector<avsm::gpu::BufferRange>& buffers)
      : gpu_(gpu), cmd_(cmd), pass_(&pass), plan_(plan), images_(images), buffers_(buffers) {}

 private:

  const PlannedAccess& access(ResourceKind kind, uint32_t index, uint32_t graph_id) const;

  const avsm::gpu::Context& gpu_;
  VkCommandBuffer cmd_;
  const PlannedPass* pass_;
  const CompiledPlan& plan_;
  const std::vector<const avsm::gpu::Image*>& images_;    // by resource index
  const std::vector<avsm::gpu::BufferRange>& buffers_;  // by resource index
};

}  // namespace rg
