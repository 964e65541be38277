// Push constants of opaque meshes seen from a light (capture_opaque.vert and .frag).
#ifndef AVSM_SHARED_PASSES_CAPTURE_OPAQUE_H
#define AVSM_SHARED_PASSES_CAPTURE_OPAQUE_H
#include "shared/gpu_struct.h"
#include "shared/mesh.h"
GPU_NAMESPACE_BEGIN

#define GPU_CAPTURE_OPAQUE_PUSH(F, A)                                           \
  F(mat4, light_from_world)                                                     \
  F(vec4, depth_plane)       /* light depth(p) = dot(xyz, p) + w */             \
  F(vec2, texel_size)        /* world size of a texel at depth d: x + y * d */  \
  F(ivec2, raster_origin)    /* LightView::raster_origin: map texel = frag - it */ \
  F(uvec2, list_tile)        /* LightView::list_tile() */                       \
  GPU_CASTER_ALPHA_PUSH(F, A)
GPU_PUSH_CONSTANTS(CaptureOpaquePush, GPU_CAPTURE_OPAQUE_PUSH)

GPU_NAMESPACE_END
#endif
