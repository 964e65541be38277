#pragma once
// The fog's froxels (shaders/passes/camera/fog/fog_scattering.comp): per froxel of the
// camera's grid (FogMedia), the radiance per metre its medium scatters towards the camera
// from every light, through each light's transmittance map, and the sky; and its
// extinction. Its receivers ask paged maps for the pages they read, as the smoke's do.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/frame/frame_inputs.h"

namespace avsm::passes {

class FogScatteringPass {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_R16G16B16A16_SFLOAT;  // rgb: radiance per metre; a: sigma_t

  FogScatteringPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // The froxels of inputs.fog's grid (transient, columns x rows x slices).
  rg::TextureHandle add_to_graph(rg::Graph& graph, FrameInputs& inputs);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
};

}  // namespace avsm::passes
