#pragma once
// The viewer's shadow level overlay: one light's receivers in the tonemapped image
// tinted by the level their surface lookup reads (from ShadowResolutionPass's results),
// the others dimmed. Shader: shaders/passes/camera/quality/shadow_level_overlay.comp
// (the colours).
#include <rendergraph/graph.h>

#include <cstdint>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"

namespace avsm::passes {

class ShadowLevelOverlayPass {
 public:
  ShadowLevelOverlayPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // Adds "shadow level overlay": tints `image` (the tonemapped output, R8G8B8A8_UNORM)
  // in place with light `light`'s levels from `resolution` (ShadowResolutionPass, same
  // size). Returns the image.
  rg::TextureHandle add_to_graph(rg::Graph& graph, rg::TextureHandle image, rg::BufferHandle resolution,
                                 uint32_t light);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
};

}  // namespace avsm::passes
