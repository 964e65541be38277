#pragma once
// The volume lighting cache: per frame and fog volume, a box of cells over the
// volume's support holding the radiance scattered towards the camera per unit sigma_s
// (sum over lights of radiance * phase * light_transmittance()), so the camera march
// and the hair fog read one trilinear fetch per step instead of every light's shadow
// map (shaders/passes/camera/volumes/volume_lighting_cache.comp, common/volume_lighting_cache.glsl).
// As in Unreal Engine 5's heterogeneous volumes, a cell spans `downsample` voxels
// (scene file "lighting_cache": {"downsample": N}, default 2), or more where finer cells
// could not show more: a cell is never finer than a march pixel's footprint at the
// volume's nearest point (a volume small on screen), nor than the finest shadow-map
// texel of any light at the volume's centre (the maps hold no finer shadow detail
// across; the reference march looks them up once per texel along the ray too), and
// never coarser than a majorant brick. The boxes of all
// volumes are stacked along z in one transient 3D image.
#include <rendergraph/graph.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_maps_fwd.h"
#include "passes/frame/view.h"
#include "passes/frame/frame_inputs.h"
#include "passes/camera/volumes/volume_pass.h"
#include "shared/volume.h"

namespace avsm::passes {

using shared::GpuCacheLayout;  // shaders/shared/volume.h

class VolumeLightingCachePass {
 public:
  static constexpr VkFormat kFormat = VK_FORMAT_R16G16B16A16_SFLOAT;

  VolumeLightingCachePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // The cells of every volume for this view (march pixels `divisor` output pixels wide),
  // stacked along z within `max_texels` per side. Throws std::invalid_argument naming
  // the volume when even brick-sized cells do not fit.
  // `light_texels`: per volume, the finest level-0 shadow-map texel (world units) of any
  // light at it (0: no shadowed light).
  static std::vector<GpuCacheLayout> plan(const std::vector<VolumeBox>& boxes, const View& view, uint32_t divisor,
                                          uint32_t max_texels, const std::vector<float>& light_texels = {});
  // The finest texel of `lights` at each box's centre.
  static std::vector<float> finest_light_texels(const std::vector<VolumeBox>& boxes,
                                                const std::vector<LightView>& lights);

  // Adds the layout upload and the cache pass and sets `inputs.cache`; the inputs'
  // volume pass must have volumes (the lights' map views give the cell size).
  void add_to_graph(rg::Graph& graph, FrameInputs& inputs);

  // Cells the last frame's cache held (every volume), for the frame report.
  uint64_t cell_count() const { return cell_count_; }

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Sampler sampler_;
  uint64_t cell_count_ = 0;
};

}  // namespace avsm::passes
