// Scene lights; mirrors passes/lights.h.
#ifndef AVSM_LIGHTS_GLSL
#define AVSM_LIGHTS_GLSL

struct GpuLight {
  vec4 position_type;        // xyz position (spot), w: 0 directional, 1 spot
  vec4 direction_cos_outer;  // xyz direction the light travels, w cos(outer cone)
  vec4 radiance_cos_inner;   // rgb colour * intensity, w cos(inner cone)
};

// Radiance arriving at `p` from light `L` (unshadowed) and the unit vector towards the light.
vec3 light_radiance(GpuLight L, vec3 p, out vec3 to_light) {
  vec3 direction = L.direction_cos_outer.xyz;
  if (L.position_type.w < 0.5) {
    to_light = -direction;
    return L.radiance_cos_inner.rgb;
  }
  vec3 d = L.position_type.xyz - p;
  float distance2 = max(dot(d, d), 1e-8);
  to_light = d * inversesqrt(distance2);
  float cos_angle = dot(-to_light, direction);
  float cone = smoothstep(L.direction_cos_outer.w, L.radiance_cos_inner.w, cos_angle);
  return L.radiance_cos_inner.rgb * cone / distance2;
}

#endif
