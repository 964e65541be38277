// A light's capture lists (shaders/common/capture_lists.glsl): per texel, a list of
// occluding segments in one node buffer. The exact (uncompressed) reference reads
// the same nodes at lookup time.
#ifndef AVSM_SHARED_CAPTURE_H
#define AVSM_SHARED_CAPTURE_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

// The end of a list, and the value the head image is cleared to.
GPU_CONST(uint, kListEnd, 0xffffffffu)

// One occluding segment: transmittance falls linearly from 1 at `entry` to
// `exit_trans` at `exit_depth` (light-space depths, world units).
#define GPU_CAPTURE_SEGMENT(F, A)                                  \
  F(float, entry)                                                  \
  F(float, exit_depth)                                             \
  F(float, exit_trans)                                             \
  F(uint, next) /* older node of the same texel, or kListEnd */
GPU_STRUCT(CaptureSegment, GPU_CAPTURE_SEGMENT)

GPU_NAMESPACE_END
#endif
