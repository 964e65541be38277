// Where the techniques' maps keep their data, for the shaders that build and read
// them and the C++ that sizes and inspects them.
#ifndef AVSM_SHARED_MAP_LAYOUTS_H
#define AVSM_SHARED_MAP_LAYOUTS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

// ---- AVSM map: one vec4 array per light ----
// Mip levels one after another; in a level, texels row by row; per texel N/4 vec4, each
// holding 4 nodes front to back, one 32-bit word per node (uint bits in the float array:
// written with uintBitsToFloat, read with floatBitsToUint): the depth in the low 16 bits,
// unorm over the light's depth range [near, far] (GpuShadow::depth_range.xy), the
// transmittance in the high 16 bits, unorm. Texels with fewer than N nodes repeat their
// last node. Offsets count vec4s.

GPU_FUNCTION uint avsm_level_size(uint resolution, uint level) { return max(resolution >> level, 1u); }

// vec4s per texel: N nodes of 4 bytes.
GPU_FUNCTION uint avsm_texel_vec4s(uint nodes) { return nodes / 4u; }

// First vec4 of mip `level`.
GPU_FUNCTION uint avsm_level_offset(uint resolution, uint nodes, uint level) {
  uint offset = 0u;
  for (uint l = 0u; l < level; ++l) {
    uint size = avsm_level_size(resolution, l);
    offset += size * size * avsm_texel_vec4s(nodes);
  }
  return offset;
}

// First vec4 of a texel's curve.
GPU_FUNCTION uint avsm_map_texel_base(uint resolution, uint nodes, uint level, uint x, uint y) {
  return avsm_level_offset(resolution, nodes, level) +
         (y * avsm_level_size(resolution, level) + x) * avsm_texel_vec4s(nodes);
}

// x in [0, 1] to 16 bits, rounded to nearest: monotonic, so node order survives (nodes
// closer than a step share a depth, and a step stays a step); 1 is the top code, so the
// cleared curve's far node (at far_depth) stays inside the range.
GPU_FUNCTION uint avsm_unorm16(float x) { return uint(min(max(x, 0.0f), 1.0f) * 65535.0f + 0.5f); }
GPU_FUNCTION float avsm_from_unorm16(uint q) { return float(q) * (1.0f / 65535.0f); }  // 65535 -> exactly 1

// One node's word. Decoding and storing again gives the same word (the mips re-store
// their children's nodes).
GPU_FUNCTION uint avsm_node_pack(float depth, float transmittance, float near_depth, float far_depth) {
  return avsm_unorm16((depth - near_depth) / max(far_depth - near_depth, 1e-20f)) |
         (avsm_unorm16(transmittance) << 16u);
}
GPU_FUNCTION float avsm_node_depth(uint node, float near_depth, float far_depth) {
  return near_depth + avsm_from_unorm16(node & 0xffffu) * (far_depth - near_depth);
}
GPU_FUNCTION float avsm_node_transmittance(uint node) { return avsm_from_unorm16(node >> 16u); }

// ---- Deep shadow map: one uint array per light ----
// [0] pool nodes allocated, [1..3] unused, [4 + 2 t] texel t's first node, [5 + 2 t]
// its node count (kDsmLost: the pool was full, or its build did not finish), then from
// word dsm_builds_base(resolution) kDsmBuildWords per texel, its build between the
// build's dispatches (dsm_build.comp's DsmBuild), then the pool from word
// dsm_pool_base(resolution): per node depth, transmittance (float bits).

GPU_CONST(uint, kDsmLost, 0xffffffffu)
GPU_CONST(uint, kDsmBuildWords, 20u)  // DsmBuild takes 17 (std430)

GPU_FUNCTION uint dsm_first_node_word(uint texel_index) { return 4u + 2u * texel_index; }
GPU_FUNCTION uint dsm_node_count_word(uint texel_index) { return 5u + 2u * texel_index; }
// On 256 bytes: the build binds the builds on their own (any storage buffer offset alignment).
GPU_FUNCTION uint dsm_builds_base(uint resolution) { return (4u + 2u * resolution * resolution + 63u) & ~63u; }
GPU_FUNCTION uint dsm_pool_base(uint resolution) {
  return (dsm_builds_base(resolution) + kDsmBuildWords * resolution * resolution + 3u) & ~3u;
}

GPU_NAMESPACE_END
#endif
