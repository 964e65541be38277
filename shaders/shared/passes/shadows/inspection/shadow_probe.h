// Push constants of transmittance at probe points (shadow_probe.comp).
#ifndef AVSM_SHARED_PASSES_SHADOW_PROBE_H
#define AVSM_SHARED_PASSES_SHADOW_PROBE_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

GPU_CONST(uint, kProbePoints, 0u)
GPU_CONST(uint, kProbeTexelCurves, 1u)
GPU_CONST(uint, kProbeSurfacePoints, 2u)  // points[2 i] a surface point, points[2 i + 1] its normal

#define GPU_SHADOW_PROBE_PUSH(F, A)                              \
  F(uint, point_count)                                           \
  F(uint, light_count)                                           \
  F(uint, mode)         /* kProbe* */
GPU_PUSH_CONSTANTS(ShadowProbePush, GPU_SHADOW_PROBE_PUSH)

GPU_NAMESPACE_END
#endif
