// The host examples' ground shading pass's push constants, declared once for its GLSL
// and the hosts' C++ with the engine's shared-struct macros (host_embed's pipeline checks
// that the two agree when it is created).
#ifndef HOST_GROUND_SHADING_H
#define HOST_GROUND_SHADING_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_GROUND_PUSH(F, A)                                                         \
  F(vec4, ground)   /* xy: world x, z of the image's corner; zw: world size along x, z */ \
  F(vec4, to_light) /* w 0: xyz the unit vector towards the light; w 1: xyz a point light's position */
GPU_PUSH_CONSTANTS(GroundPush, GPU_GROUND_PUSH)

GPU_NAMESPACE_END
#endif
