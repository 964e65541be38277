// Push constants of transmittance at probe points (shadow_probe.comp).
#ifndef AVSM_SHARED_PASSES_SHADOW_PROBE_H
#define AVSM_SHARED_PASSES_SHADOW_PROBE_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

GPU_CONST(uint, kProbePoints, 0u)
GPU_CONST(uint, kProbeTexelCurves, 1u)

#define GPU_SHADOW_PROBE_PUSH(F, A)                              \
  F(uint, point_count)                                           \
  F(uint, light_count)                                           \
  F(uint, mode)         /* kProbePoints or kProbeTexelCurves */
GPU_PUSH_CONSTANTS(ShadowProbePush, GPU_SHADOW_PROBE_PUSH)

GPU_NAMESPACE_END
#endif
