// Push constants of the fast march's full-resolution finish and composite (volume_upsample.glsl).
#ifndef AVSM_SHARED_PASSES_VOLUME_UPSAMPLE_H
#define AVSM_SHARED_PASSES_VOLUME_UPSAMPLE_H
#include "shared/volume.h"
GPU_NAMESPACE_BEGIN

#define GPU_VOLUME_UPSAMPLE_PUSH(F, A)                               \
  F(mat4, inverse_view_projection)                                   \
  F(vec3, camera_position)                                           \
  F(uint, divisor)                                                   \
  F(uvec2, output_size)                                              \
  F(uvec2, march_size)                                               \
  F(uint, volume_count)                                              \
  F(float, step_voxels)                                              \
  F(uint, flags)                     /* kMarchNoMajorantSkipping */  \
  F(uint, light_count)
GPU_PUSH_CONSTANTS(VolumeUpsamplePush, GPU_VOLUME_UPSAMPLE_PUSH)

GPU_NAMESPACE_END
#endif
