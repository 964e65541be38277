// Push constants of the fog passes (passes/camera/fog/): the froxel scattering and the
// composites onto the colour, fast (from the integrated grid) and reference (marched per
// pixel). The integration needs only the grid (shared/fog.h).
#ifndef AVSM_SHARED_PASSES_FOG_H
#define AVSM_SHARED_PASSES_FOG_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_FOG_PIXELS_PUSH(F, A)                                                          \
  F(mat4, inverse_view_projection)                                                         \
  F(uvec2, output_size)   /* the camera image in pixels */                                 \
  F(uint, light_count)                                                                     \
  F(uint, reference_steps) /* the reference composite's steps per pixel ray; else unused */   \
  F(uint, first_step)      /* the reference: this dispatch's first step, */                 \
  F(uint, dispatch_steps)  /* and how many it takes (lavapipe's loop budget) */
GPU_PUSH_CONSTANTS(FogPixelsPush, GPU_FOG_PIXELS_PUSH)

GPU_NAMESPACE_END
#endif
