// Push constants of the reference camera march (volume_march.comp).
#ifndef AVSM_SHARED_PASSES_VOLUME_MARCH_H
#define AVSM_SHARED_PASSES_VOLUME_MARCH_H
#include "shared/volume.h"
GPU_NAMESPACE_BEGIN

#define GPU_VOLUME_MARCH_PUSH(F, A)                                  \
  F(mat4, inverse_view_projection)                                   \
  F(vec3, camera_position)                                           \
  F(uint, volume_count)                                              \
  F(uvec2, image_size)                                               \
  F(uint, light_count)                                               \
  F(uint, flags)                     /* kMarchNoMajorantSkipping */
GPU_PUSH_CONSTANTS(VolumeMarchPush, GPU_VOLUME_MARCH_PUSH)

GPU_NAMESPACE_END
#endif
