#include "passes/frame/volume_density_atlas.h"

#include <nanovdb/NanoVDB.h>

#include <glm/gtc/packing.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "gpu/transfer.h"
#include "passes/camera/volumes/volume_pass.h"

namespace avsm::passes {
namespace {

// Slots per axis of a box holding `count` slots, near a cube so that no side
// outgrows the device limit before the volume is huge.
glm::ivec3 slot_box(uint32_t count, int slot_edge, uint32_t max_texels) {
  const int per_axis_limit = int(max_texels) / slot_edge;
  const int side = std::clamp(int(std::ceil(std::cbrt(double(count)))), 1, per_axis_limit);
  const int layers = int((count + uint32_t(side * side) - 1) / uint32_t(side * side));
  return {side, side, std::max(layers, 1)};
}

struct VolumeRegion {
  glm::ivec3 slots{1};
  int first_slice = 0;
  std::vector<uint32_t> slot_of_brick;  // per majorant brick
  uint32_t used = 0;
};

VolumeRegion plan_region(const scene::Volume& volume, int first_slice, uint32_t max_texels) {
  VolumeRegion region;
  region.first_slice = first_slice;
  region.slot_of_brick.assign(volume.majorant.max_density.size(), VolumeDensityAtlas::kEmptySlot);
  for (size_t b = 0; b < region.slot_of_brick.size(); ++b)
    if (volume.majorant.max_density[b] > 0.0f) region.slot_of_brick[b] = region.used++;
  region.slots = slot_box(std::max(region.used, 1u), volume.majorant.brick_size + 1, max_texels);
  return region;
}

// Copies one volume's non-empty bricks from its NanoVDB grid into the atlas texels.
void fill_region(const scene::Volume& volume, const VolumeRegion& region, glm::ivec3 atlas_size, float scale,
                 std::vector<uint16_t>& texels) {
  const auto* grid = reinterpret_cast<const nanovdb::NanoGrid<float>*>(volume.nanovdb.data());
  auto accessor = grid->getAccessor();
  const scene::MajorantGrid& m = volume.majorant;
  const int edge = m.brick_size + 1;
  for (int bz = 0; bz < m.dims.z; ++bz)
    for (int by = 0; by < m.dims.y; ++by)
      for (int bx = 0; bx < m.dims.x; ++bx) {
        const uint32_t slot = region.slot_of_brick[size_t(bx) + size_t(m.dims.x) * (size_t(by) + size_t(m.dims.y) * bz)];
        if (slot == VolumeDensityAtlas::kEmptySlot) continue;
        const glm::ivec3 slot_index(int(slot % uint32_t(region.slots.x)),
                                    int((slot / uint32_t(region.slots.x)) % uint32_t(region.slots.y)),
                                    int(slot / uint32_t(region.slots.x * region.slots.y)));
        const glm::ivec3 texel0 = slot_index * edge + glm::ivec3(0, 0, region.first_slice);
        const glm::ivec3 voxel0 = m.index_origin + glm::ivec3(bx, by, bz) * m.brick_size;
        for (int z = 0; z < edge; ++z)
          for (int y = 0; y < edge; ++y)
            for (int x = 0; x < edge; ++x) {
              const float density = accessor.getValue(nanovdb::Coord(voxel0.x + x, voxel0.y + y, voxel0.z + z));
              const glm::ivec3 t = texel0 + glm::ivec3(x, y, z);
              texels[size_t(t.x) + size_t(atlas_size.x) * (size_t(t.y) + size_t(atlas_size.y) * size_t(t.z))] =
                  uint16_t(glm::packHalf1x16(density * scale));
            }
      }
}

}  // namespace

void VolumeDensityAtlas::clear() {
  image_ = gpu::Image();
  slots_ = gpu::Buffer();
  bytes_ = 0;
}

void VolumeDensityAtlas::build(const gpu::Context& ctx, const std::vector<scene::Volume>& volumes,
                               std::vector<GpuVolume>& gpu_volumes) {
  const uint32_t max_texels = ctx.info().max_image_dimension_3d;
  std::vector<VolumeRegion> regions;
  glm::ivec3 size(1, 1, 0);
  for (size_t i = 0; i < volumes.size(); ++i) {
    regions.push_back(plan_region(volumes[i], size.z, max_texels));
    const glm::ivec3 texels = regions.back().slots * (volumes[i].majorant.brick_size + 1);
    size = glm::ivec3(std::max(size.x, texels.x), std::max(size.y, texels.y), size.z + texels.z);
    if (uint32_t(size.z) > max_texels)
      throw std::invalid_argument("VolumePass: volume " + std::to_string(i) + " '" + volumes[i].name +
                                  "' does not fit the density atlas: the volumes' non-empty bricks need " +
                                  std::to_string(size.z) + " texel slices, more than this device's 3D image limit of " +
                                  std::to_string(max_texels) + " (use larger majorant_brick_size or fewer volumes)");
  }
  size.z = std::max(size.z, 1);

  std::vector<uint16_t> texels(size_t(size.x) * size_t(size.y) * size_t(size.z), 0);
  std::vector<uint32_t> slots;
  for (size_t i = 0; i < volumes.size(); ++i) {
    const scene::Volume& volume = volumes[i];
    // Normalised so that any density range keeps R16F's relative precision.
    const float largest = std::max(std::abs(volume.stats.max), std::abs(volume.stats.min));
    const float scale = largest > 0.0f ? 1.0f / largest : 1.0f;
    fill_region(volume, regions[i], size, scale, texels);
    slots.insert(slots.end(), regions[i].slot_of_brick.begin(), regions[i].slot_of_brick.end());
    gpu_volumes[i].atlas_slots = regions[i].slots;
    gpu_volumes[i].atlas_first_slice = regions[i].first_slice;
    gpu_volumes[i].atlas_density_scale = largest > 0.0f ? largest : 1.0f;
  }

  gpu::ImageDesc desc;
  desc.width = uint32_t(size.x);
  desc.height = uint32_t(size.y);
  desc.depth = uint32_t(size.z);
  desc.volume = true;  // sampled as a sampler3D, also when it is one slice deep
  desc.format = kFormat;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "volume density atlas";
  image_ = gpu::Image::create(ctx, desc);
  gpu::upload_image(ctx, image_, texels.data(), texels.size() * sizeof(uint16_t), kLayout);
  slots_ = gpu::create_buffer_from(ctx, std::move(slots), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "volume brick slots");
  if (!sampler_.handle())
    sampler_ = gpu::Sampler(ctx, {VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                  false, VK_COMPARE_OP_LESS_OR_EQUAL, VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE,
                                  "volume density atlas"});
  bytes_ = texels.size() * sizeof(uint16_t);
}

}  // namespace avsm::passes
