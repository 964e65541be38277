// Push constants of the shadow resolution figures (shadow_resolution.comp).
#ifndef AVSM_SHARED_PASSES_SHADOW_RESOLUTION_H
#define AVSM_SHARED_PASSES_SHADOW_RESOLUTION_H
#include "shared/gpu_struct.h"
#include "shared/passes/camera/quality/shadow_resolution_results.h"
GPU_NAMESPACE_BEGIN

#define GPU_SHADOW_RESOLUTION_PUSH(F, A) \
  F(mat4, inverse_view_projection)       \
  F(vec3, camera_position)               \
  F(uint, light_count)                   \
  F(uvec2, image_size)
GPU_PUSH_CONSTANTS(ShadowResolutionPush, GPU_SHADOW_RESOLUTION_PUSH)

GPU_NAMESPACE_END
#endif
