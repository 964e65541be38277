// Transmittance from a light to a world point: the one place every camera pass
// asks about shadows (GpuShadow: shared/shadow.h).
//
// Before including, define AVSM_SHADOW_BINDING: the per-light parameters are at
// that binding, the AVSM maps at +1, and (uncompressed reference) the capture
// list heads at +2 and nodes at +3, each an array of AVSM_MAX_SHADOWED_LIGHTS.
//
// The maps' layouts are in shared/map_layouts.h. AVSM lookups search a texel's
// depths two levels deep (the course notes' 4-stride search): the last depth of each
// vec4 first, then inside the vec4 that holds the answer.
#ifndef AVSM_SHADOW_LOOKUP_GLSL
#define AVSM_SHADOW_LOOKUP_GLSL

#extension GL_GOOGLE_include_directive : require
#include "avsm/avsm_core.glsl"

#include "shared/capture.h"
#include "shared/map_layouts.h"
#include "shared/shadow.h"
#if AVSM_MAX_SHADOWED_LIGHTS != 4
#error "the per-slot chains below index each of the AVSM_MAX_SHADOWED_LIGHTS slots: extend them"
#endif

layout(std430, binding = AVSM_SHADOW_BINDING) readonly buffer ShadowParameters { GpuShadow shadows[]; };
layout(std430, binding = AVSM_SHADOW_BINDING + 1) readonly buffer AvsmMap { vec4 texels[]; }
avsm_maps[AVSM_MAX_SHADOWED_LIGHTS];
layout(binding = AVSM_SHADOW_BINDING + 2, r32ui) uniform readonly uimage2D shadow_list_heads[AVSM_MAX_SHADOWED_LIGHTS];
layout(std430, binding = AVSM_SHADOW_BINDING + 3) readonly buffer ShadowListNodes { CaptureSegment nodes[]; }
shadow_list_nodes[AVSM_MAX_SHADOWED_LIGHTS];

// The per-light arrays are indexed only with constants: lavapipe took the index of
// the first SIMD lane even when that lane was inactive in a branch (reading another
// light's data), and it lacks non-uniform indexing to ask for better.
vec4 shadow_map_texel(uint slot, uint i) {
  if (slot == 0u) return avsm_maps[0].texels[i];
  if (slot == 1u) return avsm_maps[1].texels[i];
  if (slot == 2u) return avsm_maps[2].texels[i];
  return avsm_maps[3].texels[i];
}

uint shadow_list_head(uint slot, ivec2 texel) {
  if (slot == 0u) return imageLoad(shadow_list_heads[0], texel).r;
  if (slot == 1u) return imageLoad(shadow_list_heads[1], texel).r;
  if (slot == 2u) return imageLoad(shadow_list_heads[2], texel).r;
  return imageLoad(shadow_list_heads[3], texel).r;
}

CaptureSegment shadow_list_node(uint slot, uint i) {
  if (slot == 0u) return shadow_list_nodes[0].nodes[i];
  if (slot == 1u) return shadow_list_nodes[1].nodes[i];
  if (slot == 2u) return shadow_list_nodes[2].nodes[i];
  return shadow_list_nodes[3].nodes[i];
}

float shadow_light_depth(GpuShadow s, vec3 p) { return dot(s.depth_plane.xyz, p) + s.depth_plane.w; }

float shadow_texel_size(GpuShadow s, float depth) { return s.texel_camera.x + s.texel_camera.y * depth; }

// Below this a curve counts as opaque (opaque segments end at exactly 0).
const float kShadowOpaque = 1e-4;

// shadow_texel_transmittance(s, level, texel, d): the light's technique's texel
// lookup, dispatched over the registry (passes/techniques/registry.h) by the code the
// build generates (cmake/ShadowTechniques.cmake).
#include "techniques_lookup.glsl"

// Transmittance from the light `s` describes to world point p. Point: the nearest
// texel of level 0. Bilinear: the four nearest curves evaluated at the point's
// depth and their results weighted (curves cannot be blended). Trilinear: bilinear
// in the two mip levels around the level of detail, blended. The taps run in one
// loop so the texel evaluation is compiled once: inlined per tap, it made the
// shaders that call this (the smoke march above all) several times slower on lavapipe.
float shadow_transmittance(GpuShadow s, vec3 p) {
  if (s.technique == kShadowNone) return 1.0;
  vec4 clip = s.light_from_world * vec4(p, 1.0);
  if (clip.w <= 0.0) return 1.0;  // behind a spot light: it does not shine there
  vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
  // Outside the map nothing was captured: the point is outside the caster bounds.
  if (any(lessThan(uv, vec2(0.0))) || any(greaterThan(uv, vec2(1.0)))) return 1.0;
  float d = shadow_light_depth(s, p);

  uint level = 0u;
  int levels = 1;
  float level_blend = 0.0;
  if (s.filter_mode == kFilterTrilinear && s.mip_count > 1u) {  // only techniques with mips have more than one level
    // Level of detail: a camera pixel's footprint at p over a light texel's size there.
    float pixel_size = distance(p, s.camera_position.xyz) * s.texel_camera.w;
    float lod = clamp(log2(max(pixel_size / max(shadow_texel_size(s, d), 1e-20), 1e-20)), 0.0,
                      float(s.mip_count - 1u));
    level = uint(floor(lod));
    level_blend = lod - float(level);
    levels = level + 1u < s.mip_count ? 2 : 1;
  }
  bool bilinear = s.filter_mode != kFilterPoint;
  float result = 0.0;
  for (int l = 0; l < levels; ++l) {
    uint current = level + uint(l);
    int size = int(max(s.resolution >> current, 1u));
    vec2 x = bilinear ? uv * float(size) - 0.5 : uv * float(size);
    ivec2 base = ivec2(floor(x));
    vec2 f = bilinear ? x - vec2(base) : vec2(0.0);
    int taps = bilinear ? 4 : 1;
    float level_value = 0.0;
    for (int tap = 0; tap < taps; ++tap) {
      ivec2 offset = ivec2(tap & 1, tap >> 1);
      vec2 w = mix(1.0 - f, f, vec2(offset));
      ivec2 texel = clamp(base + offset, ivec2(0), ivec2(size - 1));
      level_value += w.x * w.y * shadow_texel_transmittance(s, current, texel, d);
    }
    result += (levels == 1 ? 1.0 : (l == 0 ? 1.0 - level_blend : level_blend)) * level_value;
  }
  return result;
}

float light_transmittance(uint light_index, vec3 p) { return shadow_transmittance(shadows[light_index], p); }

// The exact transmittance (the light's capture lists, all nodes) when the frame
// kept them (ShadowOptions::keep_reference), else the technique's own.
float reference_light_transmittance(uint light_index, vec3 p) {
  uint reference = shadows[light_index].reference;
  return light_transmittance(reference == kNoReference ? light_index : reference, p);
}

// For surfaces: the point moved along its normal (towards the light's side) by a
// few texels, so a surface does not shadow itself through its own blocker segment.
vec3 shadow_surface_point(GpuShadow s, vec3 p, vec3 normal, vec3 to_light) {
  vec3 n = dot(normal, to_light) < 0.0 ? -normal : normal;
  return p + n * (s.camera_position.w * shadow_texel_size(s, shadow_light_depth(s, p)));
}

vec3 surface_lookup_point(uint light_index, vec3 p, vec3 normal, vec3 to_light) {
  return shadow_surface_point(shadows[light_index], p, normal, to_light);
}

float surface_light_transmittance(uint light_index, vec3 p, vec3 normal, vec3 to_light) {
  GpuShadow s = shadows[light_index];  // read once for the offset and the lookup
  if (s.technique == kShadowNone) return 1.0;
  return shadow_transmittance(s, shadow_surface_point(s, p, normal, to_light));
}

#endif
