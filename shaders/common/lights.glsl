// Scene lights (shared/lights.h) and the light they send to a point.
#ifndef AVSM_LIGHTS_GLSL
#define AVSM_LIGHTS_GLSL

#extension GL_GOOGLE_include_directive : require
#include "shared/lights.h"

// Spot and point lights: inverse-square falloff, windowed to reach 0 at the range
// (the window of Karis, "Real Shading in Unreal Engine 4", 2013), 1 with no range.
float light_distance_window(float distance2, float range) {
  if (range <= 0.0) return 1.0;
  float x = distance2 / (range * range);
  float w = clamp(1.0 - x * x, 0.0, 1.0);
  return w * w;
}

bool is_area_light(uint type) { return type >= kLightRect; }

// What reaches a point from an area light, taken from its centre: seen from afar a
// rectangle or disk of area A and radiance L is a point of intensity L A cos_e (cos_e: how
// squarely it faces the point), L A cos_e / (pi d^2) in the units above, a sphere L r^2 / d^2;
// never more than L (a light that fills the point's sky). Media and hair light with it;
// surfaces integrate the shape exactly (common/area_light.glsl).
float area_light_share(GpuLight L, uint type, vec3 to_light, float distance2) {
  float share;
  if (type == kLightSphere) {
    share = L.range.y * L.range.y / distance2;
  } else {
    float cos_emit = dot(L.direction_cos_outer.xyz, -to_light);
    if (L.range.w > 0.5) cos_emit = abs(cos_emit);
    float area = type == kLightRect ? 4.0 * L.range.y * L.range.z : 3.14159265 * L.range.y * L.range.y;
    share = area * max(cos_emit, 0.0) / (3.14159265 * distance2);
  }
  return min(share, 1.0) * light_distance_window(distance2, L.range.x);
}

// Radiance arriving at `p` from light `L` (unshadowed) and the unit vector towards the light.
vec3 light_radiance(GpuLight L, vec3 p, out vec3 to_light) {
  vec3 direction = L.direction_cos_outer.xyz;
  uint type = uint(L.position_type.w + 0.5);
  if (type == kLightDirectional) {
    to_light = -direction;
    return L.radiance_cos_inner.rgb;
  }
  vec3 d = L.position_type.xyz - p;
  float distance2 = max(dot(d, d), 1e-8);
  to_light = d * inversesqrt(distance2);
  if (is_area_light(type)) return L.radiance_cos_inner.rgb * area_light_share(L, type, to_light, distance2);
  float falloff = light_distance_window(distance2, L.range.x) / distance2;
  if (type == kLightPoint) return L.radiance_cos_inner.rgb * falloff;
  float cos_angle = dot(-to_light, direction);
  float cone = smoothstep(L.direction_cos_outer.w, L.radiance_cos_inner.w, cos_angle);
  return L.radiance_cos_inner.rgb * cone * falloff;
}

#endif
