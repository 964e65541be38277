#pragma once
// Every fog volume's non-empty majorant bricks copied out of NanoVDB into one 3D
// R16F image, so the fast camera march and the hair fog sample density with one
// hardware-trilinear fetch instead of eight NanoVDB tree walks (shaders/common/volume.glsl,
// "Density brick atlas"). A brick of B^3 voxels takes a slot of (B + 1)^3 texels: the
// extra layer is the trilinear reach into the next brick, so a sample never needs a
// second slot. Each volume's slots fill a box of its own, the boxes stacked along z.
// Values are stored divided by the volume's largest density (R16F keeps 11 bits of
// it) and scaled back in the shader.
#include <cstdint>
#include <memory>
#include <vector>

#include "gpu/resources.h"
#include "passes/frame/volume_data.h"
#include "scene/volume.h"
#include "shared/volume.h"

namespace avsm::gpu {
class Context;
}

namespace avsm::passes {

using shared::GpuVolume;  // shaders/shared/volume.h

class VolumeDensityAtlas {
 public:
  static constexpr uint32_t kEmptySlot = kEmptyAtlasSlot;
  static constexpr VkFormat kFormat = VK_FORMAT_R16_SFLOAT;

  // Creates the atlas image (at least `size` texels; the shaders scale by textureSize) and
  // the brick slot buffer (at least `slot_count` entries), both empty.
  void create(const gpu::Context& ctx, glm::ivec3 size, uint64_t slot_count);
  // A one-texel atlas of zero density in kLayout, to bind where there are no volumes.
  void create_empty(const gpu::Context& ctx);
  // Whether a packing's atlas and slots fit what create() made.
  bool fits(const PackedVolumes& packed) const;
  void clear();

  // One slot index per majorant brick, in the majorant buffer's order.
  const gpu::Buffer& slots() const { return slots_; }
  const gpu::Image& image() const { return image_; }
  VkImageView view() const { return image_.view(); }
  VkSampler sampler() const { return sampler_.handle(); }
  glm::ivec3 size() const { return size_; }
  uint64_t bytes() const { return bytes_; }
  static constexpr VkImageLayout kLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

 private:
  gpu::Image image_;
  gpu::Buffer slots_;
  gpu::Sampler sampler_;
  glm::ivec3 size_{0};
  uint64_t bytes_ = 0;
};

// The regions' copies into the atlas image from a buffer holding, from `buffer_offset`
// on, each volume's region texels (AtlasRegion::texels) one after the other.
std::vector<VkBufferImageCopy> atlas_copies(const std::vector<std::shared_ptr<const PreparedVolume>>& parts,
                                            const PackedVolumes& packed, VkDeviceSize buffer_offset);

}  // namespace avsm::passes
