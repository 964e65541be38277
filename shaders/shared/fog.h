// The homogeneous fog (scene/fog.h) as the fog passes read it (passes/camera/fog/): a
// header describing this frame's froxel grid, then the media, the global fog first as a
// box that holds all space. Where boxes overlap their coefficients add.
//
// The grid: froxels.x x froxels.y columns of froxel_pixels pixels a side, each cut into
// `slices` slices along the pixel rays. Slice boundary k (1..slices) lies at distance
// near * exp(log_range * k / slices) from the camera, and boundary 0 at the camera. The
// integrated grid is a storage buffer of one vec4 per froxel (rgb in-scattered radiance, a
// transmittance), froxel (x, y, k) at (k * froxels.y + y) * froxels.x + x, holding the fog
// from the camera to boundary k + 1: a buffer, so that it outlives a host's pass list
// (avsm/shadows.h) and needs no sampler.
#ifndef AVSM_SHARED_FOG_H
#define AVSM_SHARED_FOG_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_FOG_GRID(F, A)                                                          \
  F(vec4, camera_sky)     /* xyz: camera position; w: sky light scale */            \
  F(float, near)          /* distance of slice boundary 1 */                        \
  F(float, log_range)     /* log(distance of the last boundary / near) */           \
  F(uint, slices)                                                                   \
  F(uint, box_count)      /* media after the header, the global one first */        \
  F(uvec2, froxels)       /* columns across and down */                             \
  F(uint, froxel_pixels)                                                            \
  F(uint, enabled)        /* 0: no fog; the composites leave the colour as it is */
GPU_STRUCT(GpuFogGrid, GPU_FOG_GRID)

#define GPU_FOG_BOX(F, A)                                                              \
  F(vec4, box_min)        /* xyz */                                                   \
  F(vec4, box_max)        /* xyz */                                                   \
  F(vec4, scattering_g)   /* rgb: sigma_s x colour per metre; a: Henyey-Greenstein g */ \
  F(vec4, extinction)     /* x: sigma_s + sigma_a per metre; yzw unused */
GPU_STRUCT(GpuFogBox, GPU_FOG_BOX)

GPU_NAMESPACE_END
#endif
