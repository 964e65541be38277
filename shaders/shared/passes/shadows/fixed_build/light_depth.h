// Push constants of the light depth pass (shaders/passes/shadows/fixed_build/light_depth.vert and .frag).
#ifndef AVSM_SHARED_PASSES_LIGHT_DEPTH_H
#define AVSM_SHARED_PASSES_LIGHT_DEPTH_H
#include "shared/gpu_struct.h"
#include "shared/mesh.h"
GPU_NAMESPACE_BEGIN

#define GPU_LIGHT_DEPTH_PUSH(F, A) F(mat4, light_from_world) GPU_CASTER_ALPHA_PUSH(F, A)
GPU_PUSH_CONSTANTS(LightDepthPush, GPU_LIGHT_DEPTH_PUSH)

GPU_NAMESPACE_END
#endif
