// Push constants of camera opaque meshes (opaque.vert and .frag).
#ifndef AVSM_SHARED_PASSES_OPAQUE_H
#define AVSM_SHARED_PASSES_OPAQUE_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_OPAQUE_PUSH(F, A)\
  F(mat4, view_projection)  \
  F(vec4, camera_position)  \
  F(uint, material)         \
  F(uint, light_count)
GPU_PUSH_CONSTANTS(OpaquePush, GPU_OPAQUE_PUSH)

GPU_NAMESPACE_END
#endif
