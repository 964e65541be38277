// Scene lights as every shader reads them: one GpuLight per scene light, in the
// storage buffer the shaders call `Lights`.
#ifndef AVSM_SHARED_LIGHTS_H
#define AVSM_SHARED_LIGHTS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_LIGHT(F, A)                                                                        \
  F(vec4, position_type)       /* xyz: position (spot); w: 0 directional, 1 spot */           \
  F(vec4, direction_cos_outer) /* xyz: direction the light travels; w: cos(outer cone) */     \
  F(vec4, radiance_cos_inner)  /* rgb: colour * intensity; w: cos(inner cone) */
GPU_STRUCT(GpuLight, GPU_LIGHT)

GPU_NAMESPACE_END
#endif
