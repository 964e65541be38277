#pragma once
// Sampled copies of the renderer's light images (passes/shadow_debug_pass.h), so
// the panel can show every light's transmittance map and let the user click a
// texel. The renderer's own images are storage images the next frame rewrites;
// the copies are made at the end of each scene frame, in its command buffer.
#include <vulkan/vulkan.h>

#include <vector>

#include "gpu/resources.h"

namespace avsm::gpu {
class Context;
}

namespace avsm::viewer {

class LightMapTextures {
 public:
  explicit LightMapTextures(gpu::Context& ctx) : ctx_(ctx) {}

  // Records copies of `sources` (in TRANSFER_SRC_OPTIMAL, as the frame graph leaves
  // them) into the textures, which end in SHADER_READ_ONLY_OPTIMAL. Returns true
  // when textures were (re)created, so their views changed.
  bool record_copies(VkCommandBuffer cmd, const std::vector<gpu::Image>& sources);

  const std::vector<gpu::Image>& textures() const { return textures_; }

 private:
  gpu::Context& ctx_;
  std::vector<gpu::Image> textures_;
};

}  // namespace avsm::viewer
