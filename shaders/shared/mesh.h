// Opaque meshes as the shaders read them: vertices pulled from a storage buffer
// (world space; the light captures read the positions of the same buffer) and one
// GpuMaterial per material.
#ifndef AVSM_SHARED_MESH_H
#define AVSM_SHARED_MESH_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_CASTER_VERTEX(F, A) A(float, position, 3) A(float, normal, 3) A(float, uv, 2)
GPU_STRUCT(CasterVertex, GPU_CASTER_VERTEX)

#define GPU_MATERIAL(F, A)                                 \
  F(vec4, base_color)                                      \
  F(uint, alpha_mask) /* 1: discard below alpha_cutoff */  \
  F(float, alpha_cutoff)                                   \
  F(uint, has_texture)                                     \
  F(float, pad)
GPU_STRUCT(GpuMaterial, GPU_MATERIAL)

// How a mesh caster's base-colour alpha casts into the shadow maps (glTF alphaMode;
// passes/shadow_casters.h, shaders/common/caster_alpha.glsl): opaque blocks, mask blocks
// where alpha >= cutoff, blend lets 1 - alpha through.
GPU_CONST(uint, kCasterAlphaOpaque, 0u)
GPU_CONST(uint, kCasterAlphaMask, 1u)
GPU_CONST(uint, kCasterAlphaBlend, 2u)
// The members a light capture's push constants carry per draw for that (see caster_alpha.glsl).
#define GPU_CASTER_ALPHA_PUSH(F, A)                          \
  F(uint, alpha_mode)    /* kCasterAlpha* */                 \
  F(float, alpha_cutoff) /* mask: blocks where alpha >= it */ \
  F(float, alpha_factor) /* the base colour factor's alpha */

GPU_NAMESPACE_END
#endif
