#include "passes/frame/volume_data.h"

#include <nanovdb/NanoVDB.h>

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <stdexcept>
#include <string>

#include "scene/volume_scattering.h"

namespace avsm::passes {
namespace {

// NanoVDB grids must start on a 32-byte boundary (NANOVDB_DATA_ALIGNMENT).
constexpr size_t kGridAlignment = 32;
// PNanoVDB in GLSL addresses its buffer with 32-bit byte offsets.
constexpr uint64_t kMaxGridBytes = uint64_t(std::numeric_limits<uint32_t>::max()) + 1;

// The GPU reads the bytes as a NanoVDB float grid through PNanoVDB, which trusts them.
void check_grid(const scene::Volume& volume, size_t index) {
  const std::string who = volume_label(volume, index);
  if (volume.nanovdb.size() < sizeof(nanovdb::GridData))
    throw std::invalid_argument("VolumePass: " + who + " has no NanoVDB grid (" +
                                std::to_string(volume.nanovdb.size()) + " bytes)");
  const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(volume.nanovdb.data());
  if (!grid->isValid()) throw std::invalid_argument("VolumePass: " + who + " does not start with a NanoVDB grid");
  if (grid->gridType() != nanovdb::GridType::Float)
    throw std::invalid_argument("VolumePass: " + who + " holds a " + nanovdb::toStr(grid->gridType()) +
                                " grid; the march reads float density");
  if (grid->gridSize() > volume.nanovdb.size())
    throw std::invalid_argument("VolumePass: " + who + " says its grid has " + std::to_string(grid->gridSize()) +
                                " bytes but only " + std::to_string(volume.nanovdb.size()) + " are there");
}

void check_majorant(const scene::Volume& volume, size_t index) {
  const scene::MajorantGrid& m = volume.majorant;
  const uint64_t bricks = uint64_t(std::max(m.dims.x, 0)) * uint64_t(std::max(m.dims.y, 0)) * uint64_t(std::max(m.dims.z, 0));
  if (bricks == 0 || m.brick_size < 1 || bricks != m.max_density.size())
    throw std::invalid_argument("VolumePass: " + volume_label(volume, index) + " has a malformed majorant grid (" +
                                std::to_string(m.max_density.size()) + " values for " + std::to_string(m.dims.x) +
                                "x" + std::to_string(m.dims.y) + "x" + std::to_string(m.dims.z) + " bricks of " +
                                std::to_string(m.brick_size) + ")");
}

void check_optics(const scene::Volume& volume, size_t index) {
  const bool ok = std::isfinite(volume.extinction_scale) && volume.extinction_scale >= 0.0f &&
                  glm::all(glm::greaterThanEqual(volume.albedo, glm::vec3(0.0f))) &&
                  glm::all(glm::lessThanEqual(volume.albedo, glm::vec3(1.0f)));
  if (!ok)
    throw std::invalid_argument("VolumePass: " + volume_label(volume, index) +
                                " needs a finite extinction scale >= 0 and an albedo in [0, 1]");
}

// The parameter block without its offsets into the shared buffers (pack_volumes sets them).
GpuVolume to_gpu(const scene::Volume& volume) {
  GpuVolume gpu{};
  gpu.index_from_world = volume.index_from_world;
  // The trilinear support reaches one voxel beyond the active voxels (as in scene::optical_depth).
  gpu.support_min = glm::vec3(volume.active_index_min - 1);
  gpu.support_max = glm::vec3(volume.active_index_max + 1);
  gpu.step_length = kMarchStepInVoxels * volume.smallest_voxel_edge();
  gpu.extinction_scale = volume.extinction_scale;
  gpu.albedo = volume.albedo;
  gpu.majorant_origin = volume.majorant.index_origin;
  gpu.brick_size = volume.majorant.brick_size;
  gpu.majorant_dims = volume.majorant.dims;
  gpu.voxel_size = volume.smallest_voxel_edge();
  gpu.octaves = uint32_t(std::clamp(volume.multiple_scattering.octaves, 1, 8));
  gpu.octave_attenuation = volume.multiple_scattering.attenuation;
  gpu.octave_contribution = volume.multiple_scattering.contribution;
  gpu.sky_light = volume.sky_light;
  gpu.sky_offset = shared::kNoSkyLighting;
  return gpu;
}

// Slots per axis of a box holding `count` slots, near a cube so that no side
// outgrows the device limit before the volume is huge.
glm::ivec3 slot_box(uint32_t count, int slot_edge, uint32_t max_texels) {
  const int per_axis_limit = std::max(int(max_texels) / slot_edge, 1);
  const int side = std::clamp(int(std::ceil(std::cbrt(double(count)))), 1, per_axis_limit);
  const int layers = int((count + uint32_t(side * side) - 1) / uint32_t(side * side));
  return {side, side, std::max(layers, 1)};
}

// The volume's non-empty bricks copied from its NanoVDB grid into a region of their own,
// normalised by the largest density so that any range keeps R16F's relative precision.
AtlasRegion atlas_region(const scene::Volume& volume, uint32_t max_texels) {
  const scene::MajorantGrid& m = volume.majorant;
  AtlasRegion region;
  region.slot_of_brick.assign(m.max_density.size(), kEmptyAtlasSlot);
  uint32_t used = 0;
  for (size_t b = 0; b < region.slot_of_brick.size(); ++b)
    if (m.max_density[b] > 0.0f) region.slot_of_brick[b] = used++;
  const int edge = m.brick_size + 1;
  region.slots = slot_box(std::max(used, 1u), edge, max_texels);
  region.texel_size = region.slots * edge;
  region.texels.assign(size_t(region.texel_size.x) * size_t(region.texel_size.y) * size_t(region.texel_size.z), 0);
  const float largest = std::max(std::abs(volume.stats.max), std::abs(volume.stats.min));
  region.density_scale = largest > 0.0f ? largest : 1.0f;
  const float scale = 1.0f / region.density_scale;

  const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(volume.nanovdb.data());
  auto accessor = grid->getAccessor();
  const glm::ivec3 size = region.texel_size;
  for (int bz = 0; bz < m.dims.z; ++bz)
    for (int by = 0; by < m.dims.y; ++by)
      for (int bx = 0; bx < m.dims.x; ++bx) {
        const uint32_t slot = region.slot_of_brick[size_t(bx) + size_t(m.dims.x) * (size_t(by) + size_t(m.dims.y) * bz)];
        if (slot == kEmptyAtlasSlot) continue;
        const glm::ivec3 slot_index(int(slot % uint32_t(region.slots.x)),
                                    int((slot / uint32_t(region.slots.x)) % uint32_t(region.slots.y)),
                                    int(slot / uint32_t(region.slots.x * region.slots.y)));
        const glm::ivec3 texel0 = slot_index * edge;
        const glm::ivec3 voxel0 = m.index_origin + glm::ivec3(bx, by, bz) * m.brick_size;
        for (int z = 0; z < edge; ++z)
          for (int y = 0; y < edge; ++y)
            for (int x = 0; x < edge; ++x) {
              const float density = accessor.getValue(nanovdb::Coord(voxel0.x + x, voxel0.y + y, voxel0.z + z));
              const glm::ivec3 t = texel0 + glm::ivec3(x, y, z);
              region.texels[size_t(t.x) + size_t(size.x) * (size_t(t.y) + size_t(size.y) * size_t(t.z))] =
                  uint16_t(glm::packHalf1x16(density * scale));
            }
      }
  return region;
}

}  // namespace

std::string volume_label(const scene::Volume& volume, std::size_t index) {
  return "volume " + std::to_string(index) + (volume.name.empty() ? "" : " '" + volume.name + "'");
}

PreparedVolume prepare_volume(std::shared_ptr<const scene::Volume> volume, std::size_t index, uint32_t max_3d_texels) {
  check_grid(*volume, index);
  check_majorant(*volume, index);
  check_optics(*volume, index);
  PreparedVolume part;
  part.parameters = to_gpu(*volume);
  // The sky's light and the octaves' escape chance read it.
  if (volume->sky_light > 0.0f || volume->multiple_scattering.octaves > 1) part.sky = scene::sky_lighting(*volume);
  part.atlas = atlas_region(*volume, max_3d_texels);
  part.volume = std::move(volume);
  return part;
}

PackedVolumes pack_volumes(const std::vector<std::shared_ptr<const PreparedVolume>>& parts, uint32_t max_3d_texels) {
  PackedVolumes packed;
  packed.atlas_size = glm::ivec3(1, 1, 0);
  for (size_t i = 0; i < parts.size(); ++i) {
    const PreparedVolume& part = *parts[i];
    const scene::Volume& volume = *part.volume;
    const size_t grid_offset = (packed.grids.size() + kGridAlignment - 1) / kGridAlignment * kGridAlignment;
    if (grid_offset + volume.nanovdb.size() > kMaxGridBytes)
      throw std::invalid_argument("VolumePass: " + volume_label(volume, i) +
                                  " does not fit: all NanoVDB grids together must stay under 4 GiB");
    packed.grids.resize(grid_offset + volume.nanovdb.size());
    std::memcpy(packed.grids.data() + grid_offset, volume.nanovdb.data(), volume.nanovdb.size());
    GpuVolume gpu = part.parameters;
    gpu.grid_byte_offset = uint32_t(grid_offset);
    gpu.majorant_offset = uint32_t(packed.brick_grids.size());
    packed.brick_grids.insert(packed.brick_grids.end(), volume.majorant.max_density.begin(), volume.majorant.max_density.end());
    packed.slots.insert(packed.slots.end(), part.atlas.slot_of_brick.begin(), part.atlas.slot_of_brick.end());
    // The atlas regions stack along z.
    gpu.atlas_slots = part.atlas.slots;
    gpu.atlas_first_slice = packed.atlas_size.z;
    gpu.atlas_density_scale = part.atlas.density_scale;
    packed.atlas_first_slice.push_back(packed.atlas_size.z);
    packed.atlas_size = glm::ivec3(std::max(packed.atlas_size.x, part.atlas.texel_size.x),
                                   std::max(packed.atlas_size.y, part.atlas.texel_size.y),
                                   packed.atlas_size.z + part.atlas.texel_size.z);
    if (uint32_t(packed.atlas_size.z) > max_3d_texels)
      throw std::invalid_argument("VolumePass: " + volume_label(volume, i) +
                                  " does not fit the density atlas: the volumes' non-empty bricks need " +
                                  std::to_string(packed.atlas_size.z) +
                                  " texel slices, more than this device's 3D image limit of " +
                                  std::to_string(max_3d_texels) + " (use larger majorant_brick_size or fewer volumes)");
    packed.parameters.push_back(gpu);
  }
  // No sky grid starts at 0 (shared::kNoSkyLighting): they follow every majorant.
  for (size_t i = 0; i < parts.size(); ++i) {
    if (parts[i]->sky.empty()) continue;
    packed.parameters[i].sky_offset = uint32_t(packed.brick_grids.size());
    packed.brick_grids.insert(packed.brick_grids.end(), parts[i]->sky.begin(), parts[i]->sky.end());
  }
  packed.atlas_size.z = std::max(packed.atlas_size.z, 1);
  return packed;
}

}  // namespace avsm::passes
