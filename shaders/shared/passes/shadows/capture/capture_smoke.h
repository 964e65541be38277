// Push constants of smoke seen from a light (common/capture_smoke.glsl).
#ifndef AVSM_SHARED_PASSES_CAPTURE_SMOKE_H
#define AVSM_SHARED_PASSES_CAPTURE_SMOKE_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_CAPTURE_SMOKE_PUSH(F, A)                                     \
  F(mat4, world_from_light)      /* light clip -> world */               \
  F(vec4, depth_plane)           /* light depth(p) = dot(xyz, p) + w */  \
  F(uint, resolution)            /* the map's texels per side */         \
  F(uint, volume_count)                                                  \
  F(uint, samples_per_segment)                                           \
  F(uint, volume_mask)           /* VolumeCasters::volume_mask */        \
  F(uvec2, raster_origin)        /* LightView::raster_origin */          \
  F(uint, raster_resolution)     /* LightView::raster() */               \
  F(uint, pad)                                                           \
  F(uvec2, list_tile)            /* LightView::list_tile() */
GPU_PUSH_CONSTANTS(CaptureSmokePush, GPU_CAPTURE_SMOKE_PUSH)

GPU_NAMESPACE_END
#endif
