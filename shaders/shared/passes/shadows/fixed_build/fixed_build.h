// Push constants of a map built straight from the casters (shaders/common/fixed_build.glsl).
#ifndef AVSM_SHARED_PASSES_FIXED_BUILD_H
#define AVSM_SHARED_PASSES_FIXED_BUILD_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_FIXED_BUILD_PUSH(F, A)                                                       \
  F(mat4, light_from_world)     /* light clip from world */                              \
  F(vec4, depth_plane)          /* light depth(p) = dot(xyz, p) + w */                   \
  F(vec4, facing_point)         /* xyz: where hair ribbons turn to; w: the far depth */  \
  F(vec2, texel_size)           /* world size of a texel at depth d: x + y * d */        \
  F(float, near_depth)          /* the light's caster depth range starts here */         \
  F(uint, sizes)                /* fixed_build_sizes(): technique size, smoke samples    \
                                   per segment, volume count (128 bytes hold no more) */ \
  F(uint, resolution)                                                                    \
  F(uint, first_segment)        /* hair strand segments [first, first + count) */        \
  F(uint, segment_count)                                                                 \
  F(uint, volume_mask)          /* VolumeCasters::volume_mask */
GPU_PUSH_CONSTANTS(FixedBuildPush, GPU_FIXED_BUILD_PUSH)

// FixedBuildPush::sizes: technique size (avsm nodes, osm planes, fom terms; < 256) in
// bits 0..7, smoke samples per segment (< 256) in 8..15, volume count in 16..31.
GPU_FUNCTION uint fixed_build_sizes(uint technique_size, uint samples_per_segment, uint volume_count) {
  return technique_size | (samples_per_segment << 8u) | (volume_count << 16u);
}

GPU_NAMESPACE_END
#endif
