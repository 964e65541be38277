#pragma once
// A deterministic stand-in for a Vulkan device's memory requirements.
//   textures: bytes per texel x extent x layers, summed over the mip chain; alignment
//             1 KiB below 64 KiB and 64 KiB above (like "small/large page" drivers);
//             size rounded up to the alignment
//   buffers:  size rounded up to 4, alignment 256
//   classes:  everything in memory type 0 (bits 0x1), or, with split_render_targets,
//             colour/depth attachments in type 1 (bits 0x2), like drivers that keep
//             render targets in their own memory types
#include <rendergraph/memory_model.h>

namespace rg_test {

class MockMemoryModel : public rg::MemoryModel {
 public:
  struct Config {
    bool split_render_targets = false;
    uint64_t granularity = 1024;
  };

  MockMemoryModel() = default;
  explicit MockMemoryModel(Config config) : config_(config) {}

  rg::MemoryRequirements texture(const rg::TextureDesc& desc, rg::UsageSet usages, const std::string&) const override;
  rg::MemoryRequirements buffer(const rg::BufferDesc& desc, rg::UsageSet usages, const std::string&) const override;
  uint64_t buffer_image_granularity() const override { return config_.granularity; }

  static uint32_t bytes_per_texel(VkFormat format);

 private:
  Config config_;
};

}  // namespace rg_test
