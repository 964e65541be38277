// Push constants of shadow errors at hair receivers (shadow_quality_hair.comp).
#ifndef AVSM_SHARED_PASSES_SHADOW_QUALITY_HAIR_H
#define AVSM_SHARED_PASSES_SHADOW_QUALITY_HAIR_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_SHADOW_QUALITY_HAIR_PUSH(F, A)\
  F(mat4, view_projection)  \
  F(uvec2, image_size)      \
  F(uint, receiver_count)   \
  F(uint, stride)           \
  F(uint, light_count)
GPU_PUSH_CONSTANTS(ShadowQualityHairPush, GPU_SHADOW_QUALITY_HAIR_PUSH)

GPU_NAMESPACE_END
#endif
