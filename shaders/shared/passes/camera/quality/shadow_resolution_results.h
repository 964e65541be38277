// The shadow resolution figures (shadow_resolution.comp writes them, the level overlay
// reads them): per camera pixel and light, the level a surface lookup reads and how wide
// its texels are on screen.
#ifndef AVSM_SHARED_PASSES_SHADOW_RESOLUTION_RESULTS_H
#define AVSM_SHARED_PASSES_SHADOW_RESOLUTION_RESULTS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

// One light's lookup at one pixel's opaque surface.
#define GPU_PIXEL_SHADOW_RESOLUTION(F, A)                                                                   \
  F(float, level)         /* the level read, with the trilinear blend; < 0: no surface the light reaches */ \
  F(float, texel_pixels)  /* the widest a texel of that level is on screen, in pixels */                    \
  F(float, needed_texels) /* the pixel's area in the map over a square texel's that is kPagedTexelPixels  \
                             wide at its widest there: the fewest texels that cover the pixel in any map  \
                             of square texels that meets the target (whole levels take more) */           \
  F(uint, map)            /* the map record read (a point light's face, a cascade) */                       \
  F(uint, paged)          /* 1 for a paged map */
GPU_STRUCT(PixelShadowResolution, GPU_PIXEL_SHADOW_RESOLUTION)

GPU_NAMESPACE_END
#endif
