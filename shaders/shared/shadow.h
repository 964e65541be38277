// What a camera pass reads to look a light's shadows up (shaders/common/shadow_lookup.glsl):
// one GpuShadow per scene light, and per shadowed light (at most AVSM_MAX_SHADOWED_LIGHTS)
// its map and, for the exact reference, its capture lists.
#ifndef AVSM_SHARED_SHADOW_H
#define AVSM_SHARED_SHADOW_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

// Lights with a shadow map per frame. A #define, as GLSL array sizes and the lookups'
// per-slot chains (shadow_lookup.glsl checks it is 4) need it at preprocessing time.
#define AVSM_MAX_SHADOWED_LIGHTS 4
GPU_CONST(uint, kMaxShadowedLights, AVSM_MAX_SHADOWED_LIGHTS)

// GpuShadow::technique: a light without shadows; the techniques' codes follow their
// registry order from 1 (passes/techniques/registry.h).
GPU_CONST(uint, kShadowNone, 0u)
// GpuShadow::filter_mode
GPU_CONST(uint, kFilterPoint, 0u)
GPU_CONST(uint, kFilterBilinear, 1u)
GPU_CONST(uint, kFilterTrilinear, 2u)
// GpuShadow::reference when the light has no exact-reference entry
GPU_CONST(uint, kNoReference, 0xffffffffu)

#define GPU_SHADOW(F, A)                                                                                        \
  F(mat4, light_from_world) /* world -> light clip; uv = clip.xy / clip.w * 0.5 + 0.5 */                       \
  F(vec4, depth_plane)      /* light depth(p) = dot(xyz, p) + w */                                             \
  F(vec4, texel_camera)     /* x, y: level-0 texel world size = x + y * depth; z: far depth;                   \
                               w: camera radians per pixel */                                                  \
  F(vec4, camera_position)  /* xyz; w: receivers' normal offset in texels */                                   \
  F(vec4, depth_range)      /* x, y: the light's caster depth range (osm and fom normalise over it);           \
                               z: osm/fom lookup bias (depth units), against self-shadowing inside a slice */  \
  F(vec4, technique_data)   /* the technique's own lookup numbers (constant: x, its transmittance) */          \
  F(uint, technique)        /* kShadowNone, or the technique's registry code */                                \
  F(uint, node_count)       /* avsm: N nodes (a multiple of 4); osm: K planes; fom: K terms */                 \
  F(uint, resolution)       /* level-0 texels per side */                                                      \
  F(uint, mip_count)                                                                                           \
  F(uint, filter_mode)      /* kFilter* */                                                                     \
  F(uint, exponential)      /* 1: exponential interpolation between nodes */                                   \
  F(uint, slot)             /* index into the map and list arrays */                                           \
  F(uint, reference)        /* index of this light's exact-reference entry in shadows[], or kNoReference */
GPU_STRUCT(GpuShadow, GPU_SHADOW)

GPU_NAMESPACE_END
#endif
