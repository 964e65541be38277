#pragma once
// The fast camera march through the fog volumes, front part (shaders/passes/
// volume_cached_march.comp): at 1/divisor of the output resolution per axis, density
// from the brick atlas, in-scattering from the lighting cache, steps of step_voxels
// voxels, each ray up to the nearest opaque distance around its block. Writes a march
// image (rgb in-scattered radiance, a: transmittance) and the distance each march pixel
// stopped at; VolumeUpsamplePass finishes every output pixel's ray and composites.
#include <rendergraph/graph.h>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/frame/view.h"
#include "passes/frame/frame_inputs.h"
#include "passes/camera/volumes/volume_pass.h"

namespace avsm::passes {

struct VolumeMarchImage {
  rg::TextureHandle scattering;  // R16G16B16A16_SFLOAT, march size
  rg::TextureHandle distance;    // R32_SFLOAT, march size
  uint32_t divisor = 1;
};

class VolumeCachedMarchPass {
 public:
  static constexpr VkFormat kScatteringFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  static constexpr VkFormat kDistanceFormat = VK_FORMAT_R32_SFLOAT;

  VolumeCachedMarchPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // `depth`: the opaque depth (D32_SFLOAT, output size, Sampled).
  VolumeMarchImage add_to_graph(rg::Graph& graph, rg::TextureHandle depth, FrameInputs& inputs);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline cached_, with_lookups_;
  gpu::Sampler depth_sampler_;
};

}  // namespace avsm::passes
