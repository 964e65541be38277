// Scene lights as every shader reads them: one GpuLight per scene light, in the
// storage buffer the shaders call `Lights`.
#ifndef AVSM_SHARED_LIGHTS_H
#define AVSM_SHARED_LIGHTS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

// GpuLight::position_type.w
GPU_CONST(uint, kLightDirectional, 0u)
GPU_CONST(uint, kLightSpot, 1u)
GPU_CONST(uint, kLightPoint, 2u)
GPU_CONST(uint, kLightRect, 3u)    // range.yz: half width and height; range.w: 1 when two-sided
GPU_CONST(uint, kLightDisk, 4u)    // range.y: radius; range.w: 1 when two-sided
GPU_CONST(uint, kLightSphere, 5u)  // range.y: radius

// Light from the sky, the same on every surface, fibre and volume (the radiance a white
// Lambertian surface reflects under it: shaders/common/pbr_brdf.glsl); the CPU's
// volume reference (scene/volume_scattering.h) lights with it too.
GPU_CONST(vec3, kSkyAmbient, vec3(0.08, 0.1, 0.14))

#define GPU_LIGHT(F, A)                                                                        \
  F(vec4, position_type)       /* xyz: position (spot, point); w: kLight* */                  \
  F(vec4, direction_cos_outer) /* xyz: direction the light travels; w: cos(outer cone) */     \
  F(vec4, radiance_cos_inner)  /* rgb: colour * intensity; w: cos(inner cone) */              \
  F(vec4, range)               /* x: where the falloff reaches 0 (0: no limit); rect: yz half      \
                                  width and height, disk and sphere: y radius; w 1 when two-sided */
GPU_STRUCT(GpuLight, GPU_LIGHT)

// A rect light's axes from its normal n: u (its width) horizontal where it can be (across
// world up), v (its height) = n x u, so that cross(u, v) = n. A rectangle facing straight up
// or down takes u across +z instead.
GPU_FUNCTION vec3 area_light_u_axis(vec3 n) {
  vec3 reference = abs(n.y) < 0.999f ? vec3(0.0f, 1.0f, 0.0f) : vec3(0.0f, 0.0f, 1.0f);
  return normalize(cross(reference, n));
}

GPU_NAMESPACE_END
#endif
