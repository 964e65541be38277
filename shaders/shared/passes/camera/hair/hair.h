// Push constants of camera hair ribbons (hair.vert, hair_reference.frag).
#ifndef AVSM_SHARED_PASSES_HAIR_H
#define AVSM_SHARED_PASSES_HAIR_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_HAIR_PUSH(F, A)                                    \
  F(mat4, view_projection)                                     \
  F(vec4, camera_position)   /* xyz: where ribbons turn to */  \
  F(vec2, viewport)                                            \
  F(uint, light_count)                                         \
  F(float, pad)
GPU_PUSH_CONSTANTS(HairPush, GPU_HAIR_PUSH)

GPU_NAMESPACE_END
#endif
