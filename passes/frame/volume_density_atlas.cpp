#include "passes/frame/volume_density_atlas.h"

#include <algorithm>

#include "gpu/context.h"
#include "gpu/transfer.h"

namespace avsm::passes {

void VolumeDensityAtlas::clear() {
  image_ = gpu::Image();
  slots_ = gpu::Buffer();
  size_ = glm::ivec3(0);
  bytes_ = 0;
}

void VolumeDensityAtlas::create(const gpu::Context& ctx, glm::ivec3 size, uint64_t slot_count) {
  gpu::ImageDesc desc;
  desc.width = uint32_t(size.x);
  desc.height = uint32_t(size.y);
  desc.depth = uint32_t(size.z);
  desc.volume = true;  // sampled as a sampler3D, also when it is one slice deep
  desc.format = kFormat;
  desc.usage = VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "volume density atlas";
  image_ = gpu::Image::create(ctx, desc);
  slots_ = gpu::Buffer::create(ctx, {std::max<uint64_t>(slot_count, 1) * sizeof(uint32_t),
                                     VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                     gpu::MemoryLocation::DeviceLocal, "volume brick slots"});
  if (!sampler_.handle())
    sampler_ = gpu::Sampler(ctx, {VK_FILTER_LINEAR, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                                  false, VK_COMPARE_OP_LESS_OR_EQUAL, VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE,
                                  "volume density atlas"});
  size_ = size;
  bytes_ = uint64_t(size.x) * uint64_t(size.y) * uint64_t(size.z) * sizeof(uint16_t);
}

void VolumeDensityAtlas::create_empty(const gpu::Context& ctx) {
  create(ctx, glm::ivec3(1), 1);
  const uint16_t zero = 0;
  gpu::upload_image(ctx, image_, &zero, sizeof zero, kLayout);
}

bool VolumeDensityAtlas::fits(const PackedVolumes& packed) const {
  return image_ && glm::all(glm::lessThanEqual(packed.atlas_size, size_)) &&
         packed.slots.size() * sizeof(uint32_t) <= slots_.size();
}

std::vector<VkBufferImageCopy> atlas_copies(const std::vector<std::shared_ptr<const PreparedVolume>>& parts,
                                            const PackedVolumes& packed, VkDeviceSize buffer_offset) {
  std::vector<VkBufferImageCopy> copies;
  for (size_t i = 0; i < parts.size(); ++i) {
    const AtlasRegion& region = parts[i]->atlas;
    VkBufferImageCopy copy{};
    copy.bufferOffset = buffer_offset;
    copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
    copy.imageOffset = {0, 0, packed.atlas_first_slice[i]};
    copy.imageExtent = {uint32_t(region.texel_size.x), uint32_t(region.texel_size.y), uint32_t(region.texel_size.z)};
    copies.push_back(copy);
    buffer_offset += region.texels.size() * sizeof(uint16_t);
  }
  return copies;
}

}  // namespace avsm::passes
