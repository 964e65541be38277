// Push constants of the hair binning passes (shaders/passes/hair_bins_*.comp).
#ifndef AVSM_SHARED_PASSES_HAIR_BINS_H
#define AVSM_SHARED_PASSES_HAIR_BINS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_HAIR_BINS_PUSH(F, A)                                                  \
  F(mat4, view_projection)   /* light clip from world */                          \
  F(vec4, facing_point)      /* xyz: where ribbons turn to (the light) */         \
  F(uint, resolution)        /* map texels per side */                            \
  F(uint, first_segment)     /* segments [first, first + count) are binned */     \
  F(uint, segment_count)                                                          \
  F(uint, tiles_per_row)                                                          \
  F(uint, entry_capacity)    /* entries the bin buffer holds */
GPU_PUSH_CONSTANTS(HairBinsPush, GPU_HAIR_BINS_PUSH)

GPU_NAMESPACE_END
#endif
