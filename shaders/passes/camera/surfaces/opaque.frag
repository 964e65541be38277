#version 460
// glTF metallic-roughness shading (common/pbr_brdf.glsl): every light times its
// transmittance map (area lights integrated over their shape, common/area_light.glsl,
// times the mean of their virtual lights' maps), the sky, emission.
// Compiled with AVSM_AREA_SHADOW_SUBSETS 1, area lights with many virtual lights look up a
// subset of them per pixel and go to out_area_light unshadowed, for the area-shadow filter
// (shared/area_shadows.h) to multiply by their filtered transmittance.
#extension GL_GOOGLE_include_directive : require
#include "common/lights.glsl"
#include "common/pbr_brdf.glsl"
#define AVSM_SHADOW_BINDING 4
// Visible surfaces ask for the paged maps' pages they read (overdrawn ones too: alpha
// masks discard, so depth is not tested before the shader).
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 13
#include "common/shadow_lookup.glsl"
#define AVSM_LTC_BINDING 14
#include "common/area_light.glsl"

#ifndef AVSM_AREA_SHADOW_SUBSETS
#define AVSM_AREA_SHADOW_SUBSETS 0
#endif
#include "shared/area_shadows.h"
#include "shared/mesh.h"

layout(std430, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, binding = 2) readonly buffer Lights { GpuLight lights[]; };
layout(binding = 3) uniform sampler2D base_color_texture;    // sRGB
layout(binding = 8) uniform sampler2D metallic_roughness_texture;  // linear: G roughness, B metallic
layout(binding = 9) uniform sampler2D normal_texture;        // linear, tangent space
layout(binding = 10) uniform sampler2D occlusion_texture;    // linear, R
layout(binding = 11) uniform sampler2D emissive_texture;     // sRGB
#include "shared/passes/camera/surfaces/opaque.h"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 3) in vec4 in_tangent;
layout(location = 0) out vec4 out_color;
#if AVSM_AREA_SHADOW_SUBSETS
// rgb: the reflected light of the area lights that take subsets, unshadowed; a: their
// subsets' transmittance, weighted by their luminance there (1 without any).
layout(location = 1) out vec4 out_area_light;
#endif

// The normal texture's normal in world space, through the interpolated tangent frame
// (bitangent = cross(normal, tangent) x handedness); the vertex normal where the
// vertex has no tangent.
vec3 mapped_normal(GpuMaterial m, vec3 n) {
  vec3 t = in_tangent.xyz - n * dot(n, in_tangent.xyz);
  if (m.has_normal_texture == 0u || dot(t, t) < 1e-12) return n;
  t = normalize(t);
  vec3 b = cross(n, t) * (in_tangent.w < 0.0 ? -1.0 : 1.0);
  vec3 local = texture(normal_texture, in_uv).xyz * 2.0 - 1.0;
  local.xy *= m.normal_scale;
  return normalize(t * local.x + b * local.y + n * local.z);
}

void main() {
  GpuMaterial m = materials[pc.material];
  // Before any branch: derivatives are defined in uniform control flow only.
  look_up_with_pixel_steps(dFdx(in_world), dFdy(in_world));
  vec4 albedo = m.base_color;
  if (m.has_texture != 0u) albedo *= texture(base_color_texture, in_uv);
  if (m.alpha_mask != 0u && albedo.a < m.alpha_cutoff) discard;

  vec3 to_camera = normalize(pc.camera_position.xyz - in_world);
  vec3 vertex_normal = normalize(in_normal);
  // Shade the side we see: seen from behind, the whole frame (and so the bent normal) turns round.
  float side = dot(vertex_normal, to_camera) < 0.0 ? -1.0 : 1.0;
  vec3 geometric_n = side * vertex_normal;
  vec3 n = side * mapped_normal(m, vertex_normal);

  vec4 metallic_roughness = texture(metallic_roughness_texture, in_uv);
  PbrSurface surface;
  surface.base_color = albedo.rgb;
  surface.metallic = clamp(m.metallic * metallic_roughness.b, 0.0, 1.0);
  surface.roughness = clamp(m.roughness * metallic_roughness.g, 0.0, 1.0);
  float occlusion = 1.0 + m.occlusion_strength * (texture(occlusion_texture, in_uv).r - 1.0);

  vec3 lit = pbr_sky(surface, dot(n, to_camera), kSkyAmbient, occlusion);
  lit += m.emissive.rgb * texture(emissive_texture, in_uv).rgb;
  vec3 area_unshadowed = vec3(0.0);
  float area_luminance = 0.0, area_shadowed_luminance = 0.0;
  // One lookup call for every light type, so that the shadow lookup is compiled once.
  for (uint i = 0u; i < pc.light_count; ++i) {
    uint type = uint(lights[i].position_type.w + 0.5);
    vec3 to_light, reflected;
    uint subset_index = 0u, subset_size = kMaxViewsPerLight;
    bool subset = false;
    if (is_area_light(type)) {
      to_light = normalize(lights[i].position_type.xyz - in_world);  // to its centre
      reflected = area_light_reflected(lights[i], type, surface, in_world, n, to_camera);
      if (all(equal(reflected, vec3(0.0)))) continue;
#if AVSM_AREA_SHADOW_SUBSETS
      uint virtual_lights = shadows[i].views == kViewsVirtualLights ? shadows[i].view_count : 1u;
      subset = area_shadow_takes_subsets(virtual_lights);
      if (subset) {
        subset_index = area_shadow_subset(uint(gl_FragCoord.x), uint(gl_FragCoord.y), virtual_lights);
        subset_size = kAreaShadowLookups;
      }
#endif
    } else {
      vec3 radiance = light_radiance(lights[i], in_world, to_light);
      // A light behind the surface itself does not reach it, whatever the normal texture says;
      // nor does a spot outside its cone or a light beyond its range. Neither looks its map
      // up (nor asks for its pages).
      if (dot(geometric_n, to_light) <= 0.0 || dot(n, to_light) <= 0.0 || all(equal(radiance, vec3(0.0)))) continue;
      reflected = pbr_direct(surface, n, to_camera, to_light, radiance);
    }
    float t = surface_light_subset_transmittance(i, in_world, geometric_n, to_light, subset_index, subset_size);
    if (subset) {  // to the area-shadow filter, unshadowed
      float luminance = dot(reflected, vec3(0.2126, 0.7152, 0.0722));
      area_unshadowed += reflected;
      area_luminance += luminance;
      area_shadowed_luminance += luminance * t;
      continue;
    }
    lit += reflected * t;
  }
  out_color = vec4(lit, 1.0);
#if AVSM_AREA_SHADOW_SUBSETS
  out_area_light = vec4(area_unshadowed, area_luminance > 0.0 ? area_shadowed_luminance / area_luminance : 1.0);
#endif
}
