#pragma once
// Where each texel's curve lives in a light's AVSM map buffer; mirrors
// avsm_texel_base() in shaders/common/shadow_lookup.glsl. Offsets count vec4s.
#include <algorithm>
#include <cstdint>

namespace avsm::passes {

struct AvsmMapLayout {
  uint32_t resolution = 1;  // level-0 texels per side
  uint32_t nodes = 8;       // N, a multiple of 4
  uint32_t levels = 1;      // mip levels, down to 1x1 at most

  static uint32_t full_mip_count(uint32_t resolution) {
    uint32_t levels = 1;
    while ((resolution >> levels) > 0) ++levels;
    return levels;
  }
  uint32_t level_size(uint32_t level) const { return std::max(resolution >> level, 1u); }
  uint32_t vec4s_per_texel() const { return nodes / 2; }
  uint64_t level_offset(uint32_t level) const {
    uint64_t offset = 0;
    for (uint32_t l = 0; l < level; ++l) offset += uint64_t(level_size(l)) * level_size(l) * vec4s_per_texel();
    return offset;
  }
  uint64_t bytes() const { return level_offset(levels) * 16; }
};

}  // namespace avsm::passes
