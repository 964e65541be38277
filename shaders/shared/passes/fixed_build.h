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
  F(uint, technique_size)       /* avsm: nodes; osm: planes; fom: terms */               \
  F(uint, resolution)                                                                    \
  F(uint, segment_count)        /* hair strand segments */                               \
  F(uint, volume_count)                                                                  \
  F(uint, samples_per_segment)  /* smoke march samples per segment */
GPU_PUSH_CONSTANTS(FixedBuildPush, GPU_FIXED_BUILD_PUSH)

GPU_NAMESPACE_END
#endif
