#pragma once
// Where each texel's curve lives in a light's AVSM map buffer (the layout itself is
// shaders/shared/map_layouts.h, shared with the shaders). Offsets count vec4s.
#include <glm/vec4.hpp>

#include <bit>
#include <cstdint>

#include "shared/map_layouts.h"

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
  uint32_t level_size(uint32_t level) const { return shared::avsm_level_size(resolution, level); }
  uint32_t vec4s_per_texel() const { return shared::avsm_texel_vec4s(nodes); }
  uint64_t level_offset(uint32_t level) const { return shared::avsm_level_offset(resolution, nodes, level); }
  uint64_t texel_base(uint32_t level, uint32_t x, uint32_t y) const {
    return shared::avsm_map_texel_base(resolution, nodes, level, x, y);
  }
  uint64_t bytes() const { return level_offset(levels) * 16; }  // 4 bytes per node

  // Node i of a texel's curve, decoded from the texel's vec4s as read back from the map
  // (vec4s_per_texel() of them), whose nodes were stored over [near_depth, far_depth].
  struct Node {
    float depth, transmittance;
  };
  static Node node(const glm::vec4* texel, uint32_t i, float near_depth, float far_depth) {
    const uint32_t word = std::bit_cast<uint32_t>(texel[i / 4][i % 4]);
    return {shared::avsm_node_depth(word, near_depth, far_depth), shared::avsm_node_transmittance(word)};
  }
};

}  // namespace avsm::passes
