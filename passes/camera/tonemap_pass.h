#pragma once
// Linear HDR -> 8-bit display colour: exposure, a filmic curve and sRGB encoding.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"

namespace avsm::passes {

class TonemapPass {
 public:
  static constexpr VkFormat kOutputFormat = VK_FORMAT_R8G8B8A8_UNORM;  // holds sRGB-encoded values

  TonemapPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Reads `hdr`, writes `ldr` (same size); returns the written version of `ldr`.
  rg::TextureHandle add_to_graph(rg::Graph& graph, rg::TextureHandle hdr, rg::TextureHandle ldr, float exposure);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
};

}  // namespace avsm::passes
