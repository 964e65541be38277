// Push constants of the fixed-memory AVSM build (shaders/passes/avsm_fixed_build.comp).
#ifndef AVSM_SHARED_PASSES_AVSM_FIXED_BUILD_H
#define AVSM_SHARED_PASSES_AVSM_FIXED_BUILD_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_AVSM_FIXED_BUILD_PUSH(F, A)                                                  \
  F(mat4, light_from_world)     /* light clip from world */                              \
  F(vec4, depth_plane)          /* light depth(p) = dot(xyz, p) + w */                   \
  F(vec4, facing_point)         /* xyz: where hair ribbons turn to; w: the far depth */  \
  F(vec4, texel_size)           /* xy: world size of a texel at depth d: x + y * d;      \
                                   z: the near depth (nodes stored over [z, far]) */     \
  F(uint, resolution)                                                                    \
  F(uint, segment_count)        /* hair strand segments */                               \
  F(uint, volume_count)                                                                  \
  F(uint, samples_per_segment)  /* smoke march samples per inserted segment */
GPU_PUSH_CONSTANTS(AvsmFixedBuildPush, GPU_AVSM_FIXED_BUILD_PUSH)

GPU_NAMESPACE_END
#endif
