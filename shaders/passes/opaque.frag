#version 460
// Lambert + sky ambient; each light attenuated by its transmittance map.
#extension GL_GOOGLE_include_directive : require
#include "common/lights.glsl"
#define AVSM_SHADOW_BINDING 4
#include "common/shadow_lookup.glsl"

#include "shared/mesh.h"

layout(std430, binding = 1) readonly buffer Materials { GpuMaterial materials[]; };
layout(std430, binding = 2) readonly buffer Lights { GpuLight lights[]; };
layout(binding = 3) uniform sampler2D base_color_texture;
#include "shared/passes/opaque.h"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_normal;
layout(location = 2) in vec2 in_uv;
layout(location = 0) out vec4 out_color;


void main() {
  GpuMaterial m = materials[pc.material];
  vec4 albedo = m.base_color;
  if (m.has_texture != 0u) albedo *= texture(base_color_texture, in_uv);
  if (m.alpha_mask != 0u && albedo.a < m.alpha_cutoff) discard;

  vec3 n = normalize(in_normal);
  vec3 to_camera = normalize(pc.camera_position.xyz - in_world);
  if (dot(n, to_camera) < 0.0) n = -n;  // shade the side we see
  vec3 lit = kSkyAmbient;
  for (uint i = 0u; i < pc.light_count; ++i) {
    vec3 to_light;
    vec3 radiance = light_radiance(lights[i], in_world, to_light);
    float n_dot_l = dot(n, to_light);
    if (n_dot_l > 0.0) lit += radiance * n_dot_l * surface_light_transmittance(i, in_world, n, to_light);
  }
  out_color = vec4(albedo.rgb * lit, 1.0);
}
