#pragma once
// The volumes as the GPU buffers hold them, made on the CPU in two steps:
//   prepare_volume()  one volume's parts: its checks, its parameter block, its sky lighting
//                     (scene::sky_lighting) and its density atlas bricks. The costly step,
//                     and thread-safe: a sequence's frames are prepared on a worker thread
//                     (renderer/volume_sequence_player.h).
//   pack_volumes()    every volume's parts laid out in the buffers' order (grids 32-byte
//                     aligned, majorants then sky lighting, parameters, brick slots, atlas
//                     regions stacked along z): copies only.
// VolumePass uploads a packing, once at set_volumes() or each frame a sequence moves on.
#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <memory>
#include <string>
#include <vector>

#include "scene/volume.h"
#include "shared/volume.h"

namespace avsm::passes {

using shared::GpuVolume;  // shaders/shared/volume.h

// One volume's bricks in the density atlas (passes/frame/volume_density_atlas.h): its
// region of slots, (brick_size + 1)^3 texels each, filled as the atlas stores them.
struct AtlasRegion {
  glm::ivec3 slots{1};                  // slots per axis
  glm::ivec3 texel_size{0};             // slots * (brick_size + 1)
  std::vector<uint32_t> slot_of_brick;  // per majorant brick, or kEmptyAtlasSlot
  std::vector<uint16_t> texels;         // R16F, x fastest; density / density_scale
  float density_scale = 1.0f;
};
inline constexpr uint32_t kEmptyAtlasSlot = 0xffffffffu;  // kEmptyBrickSlot in volume.glsl

struct PreparedVolume {
  std::shared_ptr<const scene::Volume> volume;
  GpuVolume parameters{};   // offsets and atlas placement left for pack_volumes()
  std::vector<float> sky;   // its sky lighting grid, empty when it needs none
  AtlasRegion atlas;
};

// Sample spacing of the reference march, as a fraction of the volume's smallest voxel
// edge (GpuVolume::step_length; VolumePass::kStepInVoxels).
inline constexpr float kMarchStepInVoxels = 0.25f;

// "volume 2 'smoke'": how messages name a volume.
std::string volume_label(const scene::Volume& volume, std::size_t index);

// Checks `volume` (a usable NanoVDB float grid, a well-formed majorant grid, optics in
// range) and makes its parts. `index` names it in messages. `max_3d_texels` is the
// device's 3D image limit. Throws std::invalid_argument naming the volume.
PreparedVolume prepare_volume(std::shared_ptr<const scene::Volume> volume, std::size_t index, uint32_t max_3d_texels);

struct PackedVolumes {
  std::vector<std::byte> grids;      // NanoVDB grids, each 32-byte aligned
  std::vector<float> brick_grids;    // every majorant grid, then every sky lighting grid
  std::vector<GpuVolume> parameters;
  std::vector<uint32_t> slots;       // the atlas slot of every majorant brick, in brick_grids' order
  glm::ivec3 atlas_size{1, 1, 1};    // texels the regions need together
  std::vector<int> atlas_first_slice;  // per volume
};

// Lays the parts out. Throws std::invalid_argument when the grids pass PNanoVDB's 4 GiB
// or the atlas the device's 3D image limit, naming the volume and the setting to change.
PackedVolumes pack_volumes(const std::vector<std::shared_ptr<const PreparedVolume>>& parts, uint32_t max_3d_texels);

}  // namespace avsm::passes
