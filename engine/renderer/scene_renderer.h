#pragma once
// Renders a loaded scene through the frame graph: opaque geometry, hair, fog
// volumes, tonemapping. Owns the per-scene GPU data and the frame's output
// images; each frame declares its passes anew (the executor reuses the plan).
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <memory>

#include "gpu/resources.h"
#include "passes/hair_pass.h"
#include "passes/opaque_pass.h"
#include "passes/tonemap_pass.h"
#include "passes/view.h"
#include "passes/volume_pass.h"

#include "scene/scene.h"

namespace avsm::renderer {

class SceneRenderer {
 public:
  SceneRenderer(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const scene::Scene& scene, uint32_t width,
                uint32_t height);

  // Declares this frame's passes and binds the output images to `executor`.
  rg::Graph build_frame(rg::vulkan::Executor& executor, const passes::View& view);

  // After the frame: linear HDR and tonemapped images, both in TRANSFER_SRC_OPTIMAL.
  const gpu::Image& hdr() const { return hdr_; }
  const gpu::Image& ldr() const { return ldr_; }
  static constexpr VkImageLayout kOutputLayout = VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL;

 private:
  gpu::Context& ctx_;
  uint32_t width_, height_;
  gpu::Buffer lights_;
  uint32_t light_count_ = 0;
  passes::OpaquePass opaque_;
  passes::HairPass hair_;
  passes::VolumePass volumes_;

  passes::TonemapPass tonemap_;
  gpu::Image hdr_, ldr_;
};

}  // namespace avsm::renderer
