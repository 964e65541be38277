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
#include "passes/shadow_inputs.h"
#include "passes/view.h"
#include "passes/volume_lighting_cache_pass.h"
#include "passes/volume_pass.h"

namespace avsm::passes {

// What the fast path's camera passes read besides their own images, gathered once a
// frame: the volumes, this frame's lighting cache, and the lights and shadow maps (for
// volumes whose cache is off). Passes keep a copy until they record: the handles are
// values, and the volume pass and light buffer outlive the frame.
struct FastVolumeInputs {
  const VolumePass* volumes = nullptr;
  VolumeLightingCache cache;
  VkSampler cache_sampler = VK_NULL_HANDLE;
  VolumeShading shading;
  const gpu::Buffer* lights = nullptr;
  uint32_t light_count = 0;
  ShadowInputs shadows;

  // Whether the passes need their variant with shadow-map lookups (a volume's cache is off).
  bool map_lookups() const { return volumes->needs_map_lookups(); }
  void declare_reads(rg::PassBuilder& builder) const;
  // Volumes at `first` .. +4, the cache at +5, +6, and with map lookups the lights at +7
  // and the shadow maps from +8 (the shaders' AVSM_*_BINDING values).
  void bind(gpu::Bindings& bindings, uint32_t first, const rg::PassContext& context) const;
};

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
  VolumeMarchImage add_to_graph(rg::Graph& graph, rg::TextureHandle depth, const View& view,
                                const FastVolumeInputs& inputs);

 private:
  gpu::Context& ctx_;
  gpu::Pipeline cached_, with_lookups_;
  gpu::Sampler depth_sampler_;
};

}  // namespace avsm::passes
