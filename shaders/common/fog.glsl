// The homogeneous fog (shared/fog.h, passes/camera/fog/): its media, phase function and
// in-scattering, and the lookups of the integrated froxel grid that composite it.
//
// The includer defines AVSM_FOG_BINDING (the Fog buffer). With AVSM_FOG_INTEGRATED_BINDING
// it gets the integrated grid and the composites; with AVSM_FOG_LIGHTING it gets
// fog_in_scattering(), and has included common/lights.glsl and common/shadow_lookup.glsl
// and declared `lights`.
#ifndef AVSM_FOG_GLSL
#define AVSM_FOG_GLSL

#extension GL_GOOGLE_include_directive : require
#include "shared/fog.h"
#include "shared/lights.h"

layout(std430, binding = AVSM_FOG_BINDING) readonly buffer Fog {
  GpuFogGrid fog_grid;
  GpuFogBox fog_boxes[];
};

const float kFogPi = 3.14159265358979;

// Distance from the camera of slice boundary k (0..slices, fractional between).
float fog_boundary_distance(float k) {
  if (k <= 0.0) return 0.0;
  return fog_grid.near * exp(fog_grid.log_range * k / float(fog_grid.slices));
}

// The fractional slice boundary at `distance` (0 at the camera, slices at the grid's end).
float fog_boundary_at(float distance) {
  if (distance <= 0.0) return 0.0;
  float k = log(distance / fog_grid.near) / fog_grid.log_range * float(fog_grid.slices);
  // Between the camera and boundary 1 the boundaries are linear in distance.
  if (distance < fog_grid.near) k = distance / fog_grid.near;
  return clamp(k, 0.0, float(fog_grid.slices));
}

// The grid's far end: the fog reaches no farther (the background sees this much).
float fog_far_distance() { return fog_boundary_distance(float(fog_grid.slices)); }

struct FogMediumSample {
  vec3 scattering;   // sigma_s x colour per metre
  float extinction;  // sigma_t per metre
  float g;           // Henyey-Greenstein asymmetry, weighted by each medium's scattering
};

FogMediumSample fog_medium_at(vec3 p) {
  FogMediumSample m = FogMediumSample(vec3(0.0), 0.0, 0.0);
  float g_weight = 0.0;
  for (uint b = 0u; b < fog_grid.box_count; ++b) {
    GpuFogBox box = fog_boxes[b];
    if (any(lessThan(p, box.box_min.xyz)) || any(greaterThan(p, box.box_max.xyz))) continue;
    float weight = dot(box.scattering_g.rgb, vec3(1.0 / 3.0));
    m.scattering += box.scattering_g.rgb;
    m.extinction += box.extinction.x;
    m.g += weight * box.scattering_g.a;
    g_weight += weight;
  }
  m.g = g_weight > 0.0 ? m.g / g_weight : 0.0;
  return m;
}

// Henyey-Greenstein, normalised over the sphere; cos_theta between the light's travel and
// the scattered direction (1: straight on).
float henyey_greenstein(float cos_theta, float g) {
  float g2 = g * g;
  float denominator = max(1.0 + g2 - 2.0 * g * cos_theta, 1e-6);
  return (1.0 - g2) / (4.0 * kFogPi * denominator * sqrt(denominator));
}

// What a slice of constant medium of length `length` adds, in front of what lies behind it:
// rgb the radiance it scatters towards the camera, a its transmittance. `radiance` is the
// in-scattered radiance per metre (fog_in_scattering); the integral of a constant source
// under exp(-sigma_t x) is source x (1 - T) / sigma_t.
vec4 fog_slice(vec3 radiance, float extinction, float length) {
  float transmittance = exp(-extinction * length);
  vec3 scattered = extinction > 1e-7 ? radiance * ((1.0 - transmittance) / extinction) : radiance * length;
  return vec4(scattered, transmittance);
}

// Fog `behind` seen through fog `front` (both rgb in-scattered, a transmittance).
vec4 fog_then(vec4 front, vec4 behind) { return vec4(front.rgb + front.a * behind.rgb, front.a * behind.a); }

#ifdef AVSM_FOG_LIGHTING
// Radiance per metre the medium `m` at `p` scatters along `view_direction` (from the
// camera): every light through its transmittance map (the volumes' lookups: paged maps
// serve them from coarser levels), and the uniform sky, unshadowed.
vec3 fog_in_scattering(vec3 p, vec3 view_direction, FogMediumSample m, uint light_count) {
  if (all(equal(m.scattering, vec3(0.0)))) return vec3(0.0);
  vec3 sum = kSkyAmbient * fog_grid.camera_sky.w;
  for (uint i = 0u; i < light_count; ++i) {
    vec3 to_light;
    vec3 radiance = light_radiance(lights[i], p, to_light);
    if (all(equal(radiance, vec3(0.0)))) continue;
    sum += radiance * henyey_greenstein(dot(to_light, view_direction), m.g) * volume_light_transmittance(i, p);
  }
  return m.scattering * sum;
}
#endif

#ifdef AVSM_FOG_INTEGRATED_BINDING
layout(std430, binding = AVSM_FOG_INTEGRATED_BINDING) readonly buffer FogIntegrated { vec4 fog_integrated[]; };

vec4 fog_integrated_at(ivec3 froxel) {
  return fog_integrated[(uint(froxel.z) * fog_grid.froxels.y + uint(froxel.y)) * fog_grid.froxels.x + uint(froxel.x)];
}

// The fog between the camera and `distance` along the ray through `pixel` (pixels, a
// centre at +0.5): rgb in-scattered radiance, a transmittance. Trilinear between the
// froxel centres across the view and the slice boundaries in depth (clamped at the grid's
// edges); between the camera and the first boundary, linear from no fog.
vec4 fog_towards(vec2 pixel, float distance) {
  if (fog_grid.enabled == 0u) return vec4(0.0, 0.0, 0.0, 1.0);
  float k = fog_boundary_at(distance);
  vec3 position = vec3(pixel / float(fog_grid.froxel_pixels) - 0.5, max(k, 1.0) - 1.0);
  ivec3 last = ivec3(fog_grid.froxels, fog_grid.slices) - 1;
  position = clamp(position, vec3(0.0), vec3(last));
  ivec3 base = min(ivec3(floor(position)), last);
  vec3 f = position - vec3(base);
  vec4 fog = vec4(0.0);
  for (int corner = 0; corner < 8; ++corner) {
    ivec3 offset = ivec3(corner & 1, (corner >> 1) & 1, corner >> 2);
    vec3 w = mix(1.0 - f, f, vec3(offset));
    fog += w.x * w.y * w.z * fog_integrated_at(min(base + offset, last));
  }
  return k < 1.0 ? mix(vec4(0.0, 0.0, 0.0, 1.0), fog, k) : fog;
}

// Smoke composited over a fogged background (Deliver 3's derived composite): with the
// smoke's in-scattering and transmittance `smoke` taken at one distance `smoke_distance`
// and B the background already fogged to its own distance,
//   B' = T_s B + T_f(d_s) S_s + (1 - T_s) S_f(d_s),
// which is exact when the smoke is thin along the ray: the fog in front of the smoke
// lights and dims it, and the smoke hides the fog behind it.
vec3 smoke_over_fogged(vec3 fogged_background, vec4 smoke, vec2 pixel, float smoke_distance) {
  vec4 fog = fog_towards(pixel, smoke_distance);
  return smoke.a * fogged_background + fog.a * smoke.rgb + (1.0 - smoke.a) * fog.rgb;
}
#endif

#endif
