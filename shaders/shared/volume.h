// Volumes as the shaders read them (shaders/common/volume.glsl): one GpuVolume per
// volume, and per volume one GpuCacheLayout of the frame's lighting cache
// (shaders/common/volume_lighting_cache.glsl).
#ifndef AVSM_SHARED_VOLUME_H
#define AVSM_SHARED_VOLUME_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

// A debug flag of the camera marches: march empty bricks too (results must not change).
GPU_CONST(uint, kMarchNoMajorantSkipping, 1u)
// GpuVolume::sky_offset of a volume without sky lighting (no sky light, one octave). No
// grid starts at 0: the grids follow every volume's majorants. So a host's zeroed
// GpuVolume has none either.
GPU_CONST(uint, kNoSkyLighting, 0u)

#define GPU_VOLUME(F, A)                                                                                   \
  F(mat4, index_from_world)                                                                                \
  F(vec3, support_min)          /* index space: where the trilinear density can be non-zero */            \
  F(float, step_length)         /* world units between samples (a fraction of the smallest voxel edge) */ \
  F(vec3, support_max)                                                                                     \
  F(float, extinction_scale)    /* sigma_t = extinction_scale * density, per world unit */                \
  F(vec3, albedo)               /* sigma_s = albedo * sigma_t */                                          \
  F(uint, grid_byte_offset)     /* where this volume's NanoVDB grid starts in pnanovdb_buf_data */        \
  F(ivec3, majorant_origin)     /* index coordinate of the corner of brick (0, 0, 0) */                   \
  F(int, brick_size)            /* voxels per brick edge */                                               \
  F(ivec3, majorant_dims)       /* bricks along x, y, z (x fastest in volume_brick_grids) */              \
  F(uint, majorant_offset)      /* where this volume's majorants start in volume_brick_grids (and slots) */ \
  F(ivec3, atlas_slots)         /* this volume's region of the density atlas, slots per axis */           \
  F(int, atlas_first_slice)     /* atlas z of the region's first voxel slice */                           \
  F(float, atlas_density_scale) /* density = atlas value * this */                                        \
  F(float, voxel_size)          /* smallest voxel edge, world units */                                    \
  F(uint, octaves)              /* scattering octaves (scene::MultipleScattering; 1: single) */          \
  F(float, octave_attenuation)  /* optical depth octave k sees: attenuation^k of it */                   \
  F(float, octave_contribution) /* light octave k carries: (contribution * albedo * (1 - escape))^k */   \
  F(float, sky_light)           /* the sky's share (0: none) */                                           \
  F(uint, sky_offset)           /* its sky lighting in volume_brick_grids (4 floats per brick corner), or kNoSkyLighting */ \
  A(float, pad, 1)
GPU_STRUCT(GpuVolume, GPU_VOLUME)

#define GPU_CACHE_LAYOUT(F, A)                                                                  \
  F(mat4, world_from_cell) /* cell coordinates (cell i spans [i, i + 1)) -> world */           \
  F(vec3, cell_origin)     /* index position of cell coordinate 0 */                           \
  F(int, first_slice)      /* z of this volume's first cell slice in the cache image */        \
  F(vec3, cells_per_voxel) /* cell coordinates per index unit, per axis */                     \
  F(int, pad0)                                                                                  \
  F(ivec3, dims)           /* cells per axis */                                                \
  F(int, pad1)
GPU_STRUCT(GpuCacheLayout, GPU_CACHE_LAYOUT)

GPU_NAMESPACE_END
#endif
