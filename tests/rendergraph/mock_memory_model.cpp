#include "mock_memory_model.h"

#include <algorithm>

namespace rg_test {
namespace {

uint64_t round_up(uint64_t value, uint64_t alignment) { return (value + alignment - 1) / alignment * alignment; }

}  // namespace

uint32_t MockMemoryModel::bytes_per_texel(VkFormat format) {
  switch (format) {
    case VK_FORMAT_R8_UNORM: return 1;
    case VK_FORMAT_R8G8_UNORM:
    case VK_FORMAT_R16_SFLOAT:
    case VK_FORMAT_D16_UNORM: return 2;
    case VK_FORMAT_R16G16B16A16_SFLOAT:
    case VK_FORMAT_R32G32_UINT:
    case VK_FORMAT_R32G32_SFLOAT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT: return 8;
    case VK_FORMAT_R32G32B32A32_UINT:
    case VK_FORMAT_R32G32B32A32_SFLOAT: return 16;
    default: return 4;  // RGBA8, R32, D32, B10G11R11, ...
  }
}

rg::MemoryRequirements MockMemoryModel::texture(const rg::TextureDesc& desc, rg::UsageSet usages, const std::string&) const {
  uint64_t bytes = 0;
  for (uint32_t mip = 0; mip < desc.mip_levels; ++mip) {
    const uint64_t w = std::max(1u, desc.width >> mip), h = std::max(1u, desc.height >> mip),
                   d = std::max(1u, desc.depth >> mip);
    bytes += w * h * d;
  }
  bytes *= uint64_t{desc.array_layers} * bytes_per_texel(desc.format);

  rg::MemoryRequirements req;
  req.alignment = bytes < 64 * 1024 ? 1024 : 64 * 1024;
  req.size = round_up(bytes, req.alignment);
  const bool render_target = usages.contains(rg::Usage::ColorAttachment) ||
                             usages.contains(rg::Usage::DepthAttachmentWrite) ||
                             usages.contains(rg::Usage::DepthAttachmentRead);
  req.memory_type_bits = config_.split_render_targets && render_target ? 0x2 : 0x1;
  return req;
}

rg::MemoryRequirements MockMemoryModel::buffer(const rg::BufferDesc& desc, rg::UsageSet, const std::string&) const {
  return rg::MemoryRequirements{round_up(desc.size, 4), 256, 0x1};
}

}  // namespace rg_test
