// Opaque meshes as the shaders read them: vertices pulled from a storage buffer
// (world space; the light captures read the positions of the same buffer), a parallel
// buffer of tangents for normal textures (vec4 per vertex: unit tangent, w the
// handedness, zero where there is none; opaque pass only) and one GpuMaterial per material.
#ifndef AVSM_SHARED_MESH_H
#define AVSM_SHARED_MESH_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_CASTER_VERTEX(F, A) A(float, position, 3) A(float, normal, 3) A(float, uv, 2)
GPU_STRUCT(CasterVertex, GPU_CASTER_VERTEX)

// glTF's metallic-roughness material (scene::Material); each factor multiplies its
// texture, and a material without a texture is bound a white one (neutral for all but
// the normal texture, which has its flag).
#define GPU_MATERIAL(F, A)                                                         \
  F(vec4, base_color)                                                              \
  F(uint, alpha_mask) /* 1: discard below alpha_cutoff */                          \
  F(float, alpha_cutoff)                                                           \
  F(uint, has_texture) /* 1: base_color_texture multiplies base_color */           \
  F(float, metallic) /* x metallic_roughness_texture's B */                        \
  F(vec4, emissive) /* rgb x emissive_texture; a unused */                         \
  F(float, roughness) /* x metallic_roughness_texture's G */                       \
  F(float, normal_scale) /* the normal texture's X and Y */                        \
  F(float, occlusion_strength) /* occlusion = 1 + strength x (texture R - 1) */    \
  F(uint, has_normal_texture) /* 1: normal_texture bends the normal (tangents) */
GPU_STRUCT(GpuMaterial, GPU_MATERIAL)

// How a mesh caster's base-colour alpha casts into the shadow maps (glTF alphaMode;
// passes/shadows/shadow_casters.h, shaders/common/caster_alpha.glsl): opaque blocks, mask blocks
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
