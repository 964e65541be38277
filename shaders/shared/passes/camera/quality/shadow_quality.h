// Push constants of shadow errors per pixel against the exact lists (shadow_quality.comp).
#ifndef AVSM_SHARED_PASSES_SHADOW_QUALITY_H
#define AVSM_SHARED_PASSES_SHADOW_QUALITY_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

// One light's errors at one pixel.
#define GPU_PIXEL_SHADOW_ERROR(F, A)                                                                    \
  F(float, surface)     /* |T - T_ref| at the opaque surface; < 0: no surface the light reaches */     \
  F(float, smoke_sum)   /* sum of |T - T_ref| over the pixel's smoke receivers */                      \
  F(float, smoke_max)   /* their maximum (0 when there are none) */                                    \
  F(float, smoke_count) /* how many there are */
GPU_STRUCT(PixelShadowError, GPU_PIXEL_SHADOW_ERROR)

#define GPU_SHADOW_QUALITY_PUSH(F, A)                            \
  F(mat4, inverse_view_projection)                               \
  F(vec3, camera_position)                                       \
  F(uint, volume_count)                                          \
  F(uvec2, image_size)                                           \
  F(uint, light_count)                                           \
  F(uint, smoke_samples)             /* per volume and pixel */
GPU_PUSH_CONSTANTS(ShadowQualityPush, GPU_SHADOW_QUALITY_PUSH)

GPU_NAMESPACE_END
#endif
