#include "passes/camera/fog/fog_media.h"

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>

#include "gpu/context.h"

namespace avsm::passes {
namespace {

shared::GpuFogBox gpu_medium(const scene::FogMedium& medium, glm::vec3 box_min, glm::vec3 box_max) {
  shared::GpuFogBox box{};
  box.box_min = glm::vec4(box_min, 0.0f);
  box.box_max = glm::vec4(box_max, 0.0f);
  box.scattering_g = glm::vec4(medium.scattering * medium.color, medium.phase_g);
  box.extinction = glm::vec4(medium.scattering + medium.absorption, 0.0f, 0.0f, 0.0f);
  return box;
}

// How far the fog reaches: the setting, else the scene's farthest corner (the background
// sees through that much), never past the camera's far plane.
float fog_far_distance(const scene::Fog& fog, const View& view, const scene::Bounds& scene_bounds) {
  float far = fog.grid.distance;
  if (far <= 0.0f && !scene_bounds.empty())
    for (int c = 0; c < 8; ++c) far = std::max(far, glm::length(scene_bounds.corner(c) - view.camera_position));
  if (far <= 0.0f) far = view.far_plane;
  return std::min(far, view.far_plane);
}

}  // namespace

GpuFog gpu_fog(const scene::Fog& fog, const View& view, const scene::Bounds& scene_bounds) {
  GpuFog result;
  shared::GpuFogGrid& grid = result.grid;
  const float far = fog_far_distance(fog, view, scene_bounds);
  // Boundary 1 no nearer than 1/4096 of the way: the exponential slices then stay thick
  // enough to matter where the fog is seen.
  const float near = std::min(std::max(view.near_plane, far / 4096.0f), 0.5f * far);
  const uint32_t pixels = uint32_t(fog.grid.froxel_pixels);
  grid.camera_sky = glm::vec4(view.camera_position, fog.sky_light);
  grid.near = near;
  grid.log_range = std::log(far / near);
  grid.slices = uint32_t(fog.grid.slices);
  grid.froxels = {(view.width + pixels - 1) / pixels, (view.height + pixels - 1) / pixels};
  grid.froxel_pixels = pixels;
  grid.enabled = fog.enabled() ? 1u : 0u;
  const float everywhere = std::numeric_limits<float>::max();
  result.media.push_back(gpu_medium(fog.global, glm::vec3(-everywhere), glm::vec3(everywhere)));
  for (const scene::FogBox& box : fog.boxes) result.media.push_back(gpu_medium(box.medium, box.bounds.min, box.bounds.max));
  grid.box_count = uint32_t(result.media.size());
  return result;
}

FogGridSize fog_grid_size(const shared::GpuFogGrid& grid) { return {grid.froxels.x, grid.froxels.y, grid.slices}; }

void FogInputs::declare_reads(rg::PassBuilder& builder) const {
  if (enabled()) builder.read(integrated, rg::Usage::StorageRead);
}

void FogInputs::bind(gpu::Bindings& bindings, const rg::PassContext& context) const {
  bindings.buffer("Fog", *parameters).buffer("FogIntegrated", enabled() ? context.buffer(integrated) : *parameters);
}

FogMedia::FogMedia(gpu::Context& ctx) : ctx_(ctx) { set_fog({}, {}); }

void FogMedia::set_fog(const scene::Fog& fog, const scene::Bounds& scene_bounds) {
  fog_ = fog;
  scene_bounds_ = scene_bounds;
  // Each frame writes its own slot's copy (write()); only more boxes than it holds make them again.
  const uint64_t bytes = sizeof(shared::GpuFogGrid) + (fog.boxes.size() + 1) * sizeof(shared::GpuFogBox);
  if (buffers_ && bytes <= media_bytes_) return;
  vkDeviceWaitIdle(ctx_.device());  // frames in flight read the slots' media
  media_bytes_ = 0;  // until made: a failure leaves none to reuse
  buffers_.create(ctx_, {bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryLocation::HostUpload, "fog media"});
  media_bytes_ = bytes;
}

void FogMedia::set_frames_in_flight(uint32_t count) {
  buffers_.set_frames(ctx_, count);
  integrated_.set_frames(ctx_, count);
}

GpuFog FogMedia::describe(const View& view) const {
  GpuFog fog = gpu_fog(fog_, view, scene_bounds_);
  if (!enabled()) fog.grid.enabled = 0u;
  return fog;
}

FogInputs FogMedia::write(uint32_t slot, const View& view) {
  const GpuFog fog = describe(view);
  const FogGridSize size = fog_grid_size(fog.grid);
  const uint64_t grid_bytes = uint64_t(size.columns) * size.rows * size.slices * sizeof(glm::vec4);
  if (fog.grid.enabled && grid_bytes > integrated_bytes_) {
    vkDeviceWaitIdle(ctx_.device());  // frames in flight read the slots' grids
    integrated_bytes_ = 0;            // until made: a grid the device refuses leaves none to reuse
    // Copied from too: a host (or a test) may read the grid back.
    integrated_.create(ctx_, {grid_bytes, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
                              gpu::MemoryLocation::DeviceLocal,
                              "fog integrated", "the fog's slices or the image size (or raise its froxel_pixels)"});
    integrated_bytes_ = grid_bytes;
  }
  auto* bytes = static_cast<std::byte*>(buffers_[slot].mapped());
  std::memcpy(bytes, &fog.grid, sizeof(fog.grid));
  std::memcpy(bytes + sizeof(fog.grid), fog.media.data(), fog.media.size() * sizeof(shared::GpuFogBox));
  return {&buffers_[slot], integrated_bytes_ > 0 ? &integrated_[slot] : nullptr, size, {}};
}

}  // namespace avsm::passes
