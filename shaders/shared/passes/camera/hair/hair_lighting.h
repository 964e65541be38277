// Push constants of per strand vertex lighting and fog (common/hair_lighting.glsl).
#ifndef AVSM_SHARED_PASSES_HAIR_LIGHTING_H
#define AVSM_SHARED_PASSES_HAIR_LIGHTING_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_HAIR_LIGHTING_PUSH(F, A)\
  F(mat4, view_projection)  /* where each vertex looks the fog up */ \
  F(vec4, camera_position)  \
  F(uvec2, output_size)     \
  F(uint, point_count)      \
  F(uint, volume_count)     \
  F(uint, light_count)      \
  F(float, step_voxels)
GPU_PUSH_CONSTANTS(HairLightingPush, GPU_HAIR_LIGHTING_PUSH)

GPU_NAMESPACE_END
#endif
