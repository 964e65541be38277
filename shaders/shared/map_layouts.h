// Where the techniques' maps keep their data, for the shaders that build and read
// them and the C++ that sizes and inspects them.
#ifndef AVSM_SHARED_MAP_LAYOUTS_H
#define AVSM_SHARED_MAP_LAYOUTS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

// ---- AVSM map: one vec4 array per light ----
// Mip levels one after another; in a level, texels row by row; per texel N/4 vec4 of
// node depths, then N/4 vec4 of node transmittances (a curve is 2N floats,
// contiguous). Texels with fewer than N nodes repeat their last node. Offsets count vec4s.

GPU_FUNCTION uint avsm_level_size(uint resolution, uint level) { return max(resolution >> level, 1u); }

// First vec4 of mip `level`.
GPU_FUNCTION uint avsm_level_offset(uint resolution, uint nodes, uint level) {
  uint offset = 0u;
  for (uint l = 0u; l < level; ++l) {
    uint size = avsm_level_size(resolution, l);
    offset += size * size * (nodes / 2u);
  }
  return offset;
}

// First vec4 of a texel's curve.
GPU_FUNCTION uint avsm_map_texel_base(uint resolution, uint nodes, uint level, uint x, uint y) {
  return avsm_level_offset(resolution, nodes, level) + (y * avsm_level_size(resolution, level) + x) * (nodes / 2u);
}

// ---- Deep shadow map: one uint array per light ----
// [0] pool nodes allocated, [1..3] unused, [4 + 2 t] texel t's first node, [5 + 2 t]
// its node count (kDsmLost: the pool was full), then the pool from word
// dsm_pool_base(resolution): per node depth, transmittance (float bits).

GPU_CONST(uint, kDsmLost, 0xffffffffu)

GPU_FUNCTION uint dsm_first_node_word(uint texel_index) { return 4u + 2u * texel_index; }
GPU_FUNCTION uint dsm_node_count_word(uint texel_index) { return 5u + 2u * texel_index; }
GPU_FUNCTION uint dsm_pool_base(uint resolution) { return (4u + 2u * resolution * resolution + 3u) & ~3u; }

GPU_NAMESPACE_END
#endif
