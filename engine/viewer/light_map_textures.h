#pragma once
// Sampled copies of the renderer's light images (passes/shadows/inspection/shadow_debug_pass.h), so
// the panel can show every light's transmittance map and let the user click a
// texel. The renderer's own images are storage images the next frame rewrites;
// the copies are made at the end of each scene frame, in its command buffer.
#include <rendergraph/vulkan/executor.h>
#include <vulkan/vulkan.h>

#include <vector>

#include "gpu/resources.h"

namespace avsm::gpu {
class Context;
}

namespace avsm::viewer {

class LightMapTextures {
 public:
  LightMapTextures(gpu::Context& ctx, gpu::TimestampMode timestamps);

  // Records copies of `sources` (in TRANSFER_SRC_OPTIMAL, as the frame graph leaves
  // them) into the textures, which end in SHADER_READ_ONLY_OPTIMAL, as passes of a small
  // frame graph of their own. Returns true when textures were (re)created, so their
  // views changed.
  bool record_copies(VkCommandBuffer cmd, const std::vector<gpu::Image>& sources);

  const std::vector<gpu::Image>& textures() const { return textures_; }
  // Whether record_copies(sources) would (re)create the textures, destroying the ones
  // frames in flight may still sample.
  bool would_recreate(const std::vector<gpu::Image>& sources) const;

 private:
  // (Re)creates the textures when the sources' count or sizes changed; true if it did.
  bool match_sources(const std::vector<gpu::Image>& sources);
  void add_copy_pass(rg::Graph& graph, const gpu::Image& source, const gpu::Image& texture, size_t index);

  gpu::Context& ctx_;
  std::vector<gpu::Image> textures_;
  // Not the scene's executor: that one's plan and transients serve the scene graph
  // recorded just before into the same command buffer.
  rg::vulkan::Executor executor_;
};

}  // namespace avsm::viewer
