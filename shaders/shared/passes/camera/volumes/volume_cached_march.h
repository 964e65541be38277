// Push constants of the fast camera march at reduced resolution (volume_cached_march.glsl).
#ifndef AVSM_SHARED_PASSES_VOLUME_CACHED_MARCH_H
#define AVSM_SHARED_PASSES_VOLUME_CACHED_MARCH_H
#include "shared/volume.h"
GPU_NAMESPACE_BEGIN

#define GPU_VOLUME_CACHED_MARCH_PUSH(F, A)                           \
  F(mat4, inverse_view_projection)                                   \
  F(vec3, camera_position)                                           \
  F(uint, volume_count)                                              \
  F(uvec2, output_size)                                              \
  F(uvec2, march_size)                                               \
  F(uint, divisor)                                                   \
  F(float, step_voxels)                                              \
  F(uint, flags)                     /* kMarchNoMajorantSkipping */  \
  F(uint, light_count)
GPU_PUSH_CONSTANTS(VolumeCachedMarchPush, GPU_VOLUME_CACHED_MARCH_PUSH)

GPU_NAMESPACE_END
#endif
