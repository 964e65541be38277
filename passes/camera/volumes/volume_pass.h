#pragma once
// Fog volumes on the GPU, and the reference camera march through them.
//
// VolumePass owns every volume's data (NanoVDB grids, majorants and sky lighting,
// parameter blocks, the density brick atlas) for all passes that read volumes. Its own pass is the reference
// camera march (--volume-shading reference): it ray-marches every volume for every
// pixel, up to the opaque depth, and composites onto the lit colour in place:
//   color = color * T_camera + in-scattered light.
// The fast path's passes (lighting cache, cached march, composite) read the same data.
// In-scattering at each sample is sigma_s * phase * sum over lights of
// light_radiance() * light_transmittance() * T_camera so far, with an isotropic phase
// function; light_transmittance() (shaders/common/shadow_lookup.glsl) reads each
// light's transmittance map, so smoke shadows itself and is shadowed by hair and meshes.
// Multiple scattering adds octaves of that (scene::MultipleScattering), and the sky adds
// its light through the volume itself (scene::sky_lighting, scene/volume_scattering.h):
// shaders/common/scattered_light.glsl.
//
// The volumes are read straight from their NanoVDB grids (PNanoVDB in GLSL, trilinear,
// like scene::sample_density) with no dense 3D texture. All grids share one storage
// buffer, each at its own 32-byte-aligned offset, so one dispatch can march every
// volume per pixel in front-to-back order. The majorant bricks (max density per brick
// of voxels) let the march skip empty space. Shaders: shaders/passes/camera/volumes/volume_march.comp,
// shaders/common/volume.glsl.
#include <rendergraph/graph.h>

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <memory>
#include <cstddef>
#include <cstdint>
#include <vector>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/shadow_casters.h"
#include "passes/shadows/shadow_maps_fwd.h"
#include "passes/frame/view.h"
#include "passes/frame/frames_in_flight.h"
#include "passes/frame/volume_data.h"
#include "passes/frame/volume_density_atlas.h"
#include "scene/volume.h"
#include "shared/volume.h"

namespace avsm::passes {

struct FrameInputs;  // passes/frame/frame_inputs.h
struct FogInputs;    // passes/camera/fog/fog_media.h

using shared::GpuVolume;  // shaders/shared/volume.h

using scene::VolumeShading;

// Binds the volumes for a pass that reads them (shaders/common/volume.glsl): the NanoVDB
// grids, the majorants and the parameter blocks, and with the atlas the density atlas
// and its brick slots.
void bind_volumes(gpu::Bindings& bindings, const VolumeCasters& volumes, bool with_atlas);

// What the lighting cache needs of one volume on the CPU (passes/camera/volumes/volume_lighting_cache_pass.h).
struct VolumeBox {
  glm::mat4 world_from_index{1.0f};
  glm::vec3 support_min{0.0f}, support_max{0.0f};  // index space
  float voxel_size = 1.0f;                          // smallest voxel edge, world units
  int brick_size = 8;
  scene::Bounds world_bounds;
  float cache_downsample = 2.0f;                    // voxels per cache cell, at least
  bool cached = true;                               // false: lighting_cache "off", no cells
};

class VolumePass {
 public:
  static constexpr VkFormat kColorFormat = VK_FORMAT_R16G16B16A16_SFLOAT;
  static constexpr VkFormat kDepthFormat = VK_FORMAT_D32_SFLOAT;
  // Sample spacing as a fraction of the volume's smallest voxel edge: the same spacing
  // as the CPU reference (scene::optical_depth), fine enough that the midpoint rule
  // agrees with it to well under 1% on real smoke.
  static constexpr float kStepInVoxels = kMarchStepInVoxels;

  VolumePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // Uploads every volume: its NanoVDB bytes (all volumes in one storage buffer), its
  // majorant grid, and its parameter block (transforms, bounds, extinction scale, albedo).
  // Replaces what an earlier call uploaded (call it between frames: the old buffers go
  // at once); an empty list turns the pass off. Throws std::invalid_argument naming the
  // volume if one is not a usable NanoVDB float grid or has a malformed majorant grid.
  void set_volumes(const std::vector<scene::Volume>& volumes);
  // The same from volumes already prepared (passes/frame/volume_data.h).
  void set_prepared(std::vector<std::shared_ptr<const PreparedVolume>> parts);
  const std::vector<std::shared_ptr<const PreparedVolume>>& prepared() const { return parts_; }

  // Streaming (a volume sequence moving on): `parts` replace the volumes (as many as
  // there are) in the frame declared next into `slot`, whose previous frame completed.
  // They are written into the slot's staging buffer, and add_upload() copies them into
  // the volumes' buffers at the start of that frame, so the CPU never waits for the GPU
  // and no frame in flight sees its data change. Only a packing larger than any before
  // waits for the device, to make the buffers anew with room to grow (StreamStats).
  void stream(std::vector<std::shared_ptr<const PreparedVolume>> parts, uint32_t slot);
  // Declares the slot's staged copies as the graph's first pass ("volume upload"), if any.
  void add_upload(rg::Graph& graph, uint32_t slot);
  struct StreamStats {
    uint64_t frames = 0;         // stream() calls
    uint64_t reallocations = 0;  // of those, the ones that made the buffers anew
  };
  const StreamStats& stream_stats() const { return stream_stats_; }

  // Marches the volumes from the camera for every pixel, stopping at the opaque depth,
  // and composites onto `color` in place. Returns the written version of `color`, or
  // `color` itself when there are no volumes (no pass is added). `lights` must hold at
  // least max(light_count, 1) GpuLight entries (passes/frame/lights.h) and outlive the frame.
  rg::TextureHandle add_to_graph(rg::Graph& graph, rg::TextureHandle color /*R16G16B16A16_SFLOAT, StorageReadWrite*/,
                                 rg::TextureHandle depth /*D32_SFLOAT, Sampled*/, FrameInputs& frame);

  // Debug switch: march through empty bricks too. The image must not change; it only
  // exists so tests can check that skipping never drops density.
  void set_majorant_skipping(bool enabled) { majorant_skipping_ = enabled; }
  bool majorant_skipping() const { return majorant_skipping_; }

  uint32_t volume_count() const { return volume_count_; }
  // The volumes, shared with the light capture (passes/shadows/capture/capture_smoke_pass.h) and every
  // pass that reads them (bind_volumes). Valid handles (placeholders, volume_count 0)
  // when there are no volumes, so shaders always have something to bind.
  VolumeCasters casters() const;
  const std::vector<VolumeBox>& boxes() const { return boxes_; }
  // Some volume has its lighting cache off: the fast march must look the maps up.
  bool needs_map_lookups() const {
    return std::any_of(boxes_.begin(), boxes_.end(), [](const VolumeBox& box) { return !box.cached; });
  }
  const VolumeDensityAtlas& atlas() const { return atlas_; }

 private:
  static void check_targets(const rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth);
  using Parts = std::vector<std::shared_ptr<const PreparedVolume>>;
  // A staged packing: the staging buffer, what to copy from it where, and the volumes it holds.
  struct Upload {
    VkBuffer staging = VK_NULL_HANDLE;
    std::vector<std::pair<VkBuffer, VkBufferCopy>> copies;
    std::vector<VkBufferImageCopy> atlas;
    Parts parts;
  };
  // Makes the buffers and atlas for `packed`, `headroom` times its sizes.
  void allocate(const PackedVolumes& packed, const Parts& parts, double headroom);
  bool fits(const PackedVolumes& packed) const;
  Upload stage(const PackedVolumes& packed, const Parts& parts, gpu::Buffer& staging);
  void upload_now(const PackedVolumes& packed, const Parts& parts);  // waits for the copies
  void record_upload(VkCommandBuffer cmd, const Upload& upload);
  // The CPU's description of what the GPU holds (boxes, count) from now on.
  void describe(const Parts& parts);
  void record(rg::PassContext& c, rg::TextureHandle color, rg::TextureHandle depth, const View& view,
              const gpu::Buffer& lights, uint32_t light_count, const ShadowInputs& shadows, const FogInputs& fog,
              rg::BufferHandle page_requests, bool majorant_skipping) const;

  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Sampler depth_sampler_;
  gpu::Buffer grids_;       // every NanoVDB grid, 32-byte aligned
  gpu::Buffer brick_grids_;  // every majorant grid, then every sky lighting grid (floats)
  gpu::Buffer parameters_;  // one GpuVolume per volume
  gpu::Buffer placeholder_;  // bound for the volume buffers when there are no volumes
  VolumeDensityAtlas atlas_;
  bool atlas_initialized_ = false;  // in kLayout since its last upload
  std::vector<VolumeBox> boxes_;
  uint32_t volume_count_ = 0;
  Parts parts_;  // as last set or streamed
  std::array<gpu::Buffer, kMaxFramesInFlight> staging_;  // per frame slot
  std::array<Upload, kMaxFramesInFlight> pending_;
  StreamStats stream_stats_;
  bool majorant_skipping_ = true;
};

}  // namespace avsm::passes
