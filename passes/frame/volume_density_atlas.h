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
#include <vector>

#include "gpu/resources.h"
#include "scene/volume.h"
#include "shared/volume.h"

namespace avsm::gpu {
class Context;
}

namespace avsm::passes {

using shared::GpuVolume;  // shaders/shared/volume.h

class VolumeDensityAtlas {
 public:
  static constexpr uint32_t kEmptySlot = 0xffffffffu;  // kEmptyBrickSlot in volume.glsl
  static constexpr VkFormat kFormat = VK_FORMAT_R16_SFLOAT;

  // Builds the atlas of `volumes` and fills the atlas fields of their parameter
  // blocks (parallel to `volumes`). Throws std::invalid_argument naming the volume
  // when the atlas would exceed the device's 3D image size.
  void build(const gpu::Context& ctx, const std::vector<scene::Volume>& volumes, std::vector<GpuVolume>& gpu_volumes);
  void clear();

  // One slot index per majorant brick, in the majorant buffer's order.
  const gpu::Buffer& slots() const { return slots_; }
  VkImageView view() const { return image_.view(); }
  VkSampler sampler() const { return sampler_.handle(); }
  uint64_t bytes() const { return bytes_; }
  static constexpr VkImageLayout kLayout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;

 private:
  gpu::Image image_;
  gpu::Buffer slots_;
  gpu::Sampler sampler_;
  uint64_t bytes_ = 0;
};

}  // namespace avsm::passes
