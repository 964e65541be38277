// Push constants of the AVSM mip builder (avsm_mips.comp): one dispatch per level, built from the level above.
#ifndef AVSM_SHARED_PASSES_AVSM_MIPS_H
#define AVSM_SHARED_PASSES_AVSM_MIPS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_AVSM_MIPS_PUSH(F, A)                                                  \
  F(uint, source_offset)  /* first vec4 of the level above */                     \
  F(uint, source_size)    /* its texels per side */                               \
  F(uint, target_offset)  /* first vec4 of this level */                          \
  F(uint, target_size)                                                            \
  F(uint, node_count)                                                             \
  F(float, near_depth)    /* the light's depth range the nodes are stored over */ \
  F(float, far_depth)
GPU_PUSH_CONSTANTS(AvsmMipsPush, GPU_AVSM_MIPS_PUSH)

GPU_NAMESPACE_END
#endif
