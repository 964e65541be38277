// Area lights on surfaces (scene::LightType rect, disk, sphere): the engine's BRDF
// (common/pbr_brdf.glsl) integrated over the light with linearly transformed cosines
// (common/area_light_ltc.glsl, our fit in engine/lighting/): Lambert exactly (its form
// factor; a disk as a 16-gon of its area, a sphere as its silhouette's disk), GGX through
// the fitted table. The includer defines AVSM_LTC_BINDING (the table's two textures at it
// and the next binding) and has included common/lights.glsl and common/pbr_brdf.glsl.
#ifndef AVSM_AREA_LIGHT_GLSL
#define AVSM_AREA_LIGHT_GLSL

#extension GL_GOOGLE_include_directive : require
#include "common/area_light_ltc.glsl"

layout(binding = AVSM_LTC_BINDING) uniform sampler2D ltc_matrix_table;          // rgba: M^-1's m00, m02, m20, m22
layout(binding = AVSM_LTC_BINDING + 1) uniform sampler2D ltc_magnitude_table;   // rg: norm, fresnel

// The lobe's share of area light L (of type `type`, centre c relative to the shading point),
// its directions mapped into the cosine's space by to_cosine.
float area_light_lobe_share(GpuLight L, uint type, mat3 to_cosine, vec3 c) {
  if (type == kLightSphere) return ltc_sphere_integral(to_cosine, c, L.range.y);
  vec3 normal = L.direction_cos_outer.xyz;
  vec3 u_axis = area_light_u_axis(normal);
  vec3 v_axis = cross(normal, u_axis);
  bool two_sided = L.range.w > 0.5;
  if (type == kLightDisk) return ltc_disk_integral(to_cosine, c, u_axis, v_axis, L.range.y, two_sided);
  vec3 half_width = u_axis * L.range.y, half_height = v_axis * L.range.z;
  // Counter-clockwise seen from the side it faces: cross(p1 - p0, p3 - p0) is its normal.
  return ltc_rect_integral(to_cosine, c - half_width - half_height, c + half_width - half_height,
                           c + half_width + half_height, c - half_width + half_height, two_sided);
}

// Radiance towards v reflected at p (normal n) from area light L, unshadowed: L's radiance
// times the diffuse form factor and the specular lobe's share of the light. The diffuse
// part keeps what Fresnel leaves it, 1 - F(v . h), with h halfway to the light's centre
// (pbr_brdf takes h per light direction).
vec3 area_light_reflected(GpuLight L, uint type, PbrSurface s, vec3 p, vec3 n, vec3 v) {
  vec3 c = L.position_type.xyz - p;
  mat3 frame = ltc_shading_frame(n, v);
  float form_factor = area_light_lobe_share(L, type, frame, c);
  if (form_factor <= 0.0) return vec3(0.0);
  float n_dot_v = clamp(dot(n, v), 1e-4, 1.0);
  vec2 uv = ltc_table_uv(s.roughness, n_dot_v, float(textureSize(ltc_matrix_table, 0).x));
  vec4 inverse_matrix = textureLod(ltc_matrix_table, uv, 0.0);
  vec2 magnitude = textureLod(ltc_magnitude_table, uv, 0.0).rg;
  float specular_share = area_light_lobe_share(L, type, ltc_inverse_matrix(inverse_matrix) * frame, c);
  vec3 f0 = pbr_f0(s);
  vec3 specular = ltc_specular_magnitude(magnitude.x, magnitude.y, f0) * specular_share;
  vec3 half_to_centre = normalize(normalize(c) + v);
  vec3 diffuse_share = vec3(1.0) - pbr_schlick_fresnel(f0, clamp(dot(v, half_to_centre), 0.0, 1.0));
  vec3 diffuse = diffuse_share * s.base_color * (1.0 - s.metallic) * form_factor;
  return L.radiance_cos_inner.rgb * light_distance_window(dot(c, c), L.range.x) * (diffuse + specular);
}

#endif
