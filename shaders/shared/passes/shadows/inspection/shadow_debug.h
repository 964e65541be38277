// Push constants of a light's map seen as an image (shadow_debug.comp).
#ifndef AVSM_SHARED_PASSES_SHADOW_DEBUG_H
#define AVSM_SHARED_PASSES_SHADOW_DEBUG_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_SHADOW_DEBUG_PUSH(F, A) F(uint, light)
GPU_PUSH_CONSTANTS(ShadowDebugPush, GPU_SHADOW_DEBUG_PUSH)

GPU_NAMESPACE_END
#endif
