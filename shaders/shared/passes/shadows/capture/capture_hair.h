// Push constants of hair ribbons seen from a light (capture_hair.vert and .frag).
#ifndef AVSM_SHARED_PASSES_CAPTURE_HAIR_H
#define AVSM_SHARED_PASSES_CAPTURE_HAIR_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_CAPTURE_HAIR_PUSH(F, A)                                             \
  F(mat4, view_projection)   /* light clip from world */                        \
  F(vec4, facing_point)      /* xyz: where ribbons turn to (the light) */       \
  F(vec2, viewport)                                                             \
  F(ivec2, raster_origin)    /* LightView::raster_origin: map texel = frag - it */ \
  F(vec4, depth_plane)       /* light depth(p) = dot(xyz, p) + w */             \
  F(vec2, texel_size)        /* world size of a texel at depth d: x + y * d */  \
  F(uvec2, list_tile)        /* LightView::list_tile() */
GPU_PUSH_CONSTANTS(CaptureHairPush, GPU_CAPTURE_HAIR_PUSH)

GPU_NAMESPACE_END
#endif
