#pragma once
// Finishes the fast camera march at full resolution and composites it onto the colour
// in place, color = color * T + in-scattered (shaders/passes/camera/volumes/volume_upsample.comp): the
// reduced-resolution front parts (passes/camera/volumes/volume_cached_march_pass.h) are upsampled
// (bilinear, or nearest-depth at opaque edges), and each pixel marches the rest of its
// own ray, from where they stopped to its opaque surface.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/frame/view.h"
#include "passes/camera/volumes/volume_cached_march_pass.h"

namespace avsm::passes {

class VolumeUpsamplePass {
 public:
  VolumeUpsamplePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // `color`: R16G16B16A16_SFLOAT, read and written; `depth`: D32_SFLOAT. Returns the new colour.
  rg::TextureHandle add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                 const VolumeMarchImage& march, FrameInputs& inputs);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline cached_, with_lookups_;
  gpu::Sampler nearest_;
};

}  // namespace avsm::passes
