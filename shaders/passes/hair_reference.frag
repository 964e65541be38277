#version 460
// Hair fragments, reference path: Kajiya-Kay diffuse for fibres (light scatters by
// the sine of the angle to the tangent) with every light's shadow lookup per fragment,
// seen through the smoke in front of the strand as in hair.frag.
#extension GL_GOOGLE_include_directive : require
#include "common/lights.glsl"
#define AVSM_SHADOW_BINDING 4
#include "common/shadow_lookup.glsl"

layout(std430, binding = 3) readonly buffer Lights { GpuLight lights[]; };
layout(push_constant) uniform Push {
  mat4 view_projection;
  vec4 camera_position;
  vec2 viewport;
  uint light_count;
  float pad;
} pc;

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_tangent;
layout(location = 2) flat in vec4 in_color_opacity;
layout(location = 4) in vec4 in_fog;
layout(location = 0) out vec4 out_color;

const vec3 kSkyAmbient = vec3(0.08, 0.1, 0.14);  // as in common/hair_lighting.glsl

void main() {
  vec3 t = normalize(in_tangent);
  vec3 lit = kSkyAmbient;
  for (uint i = 0u; i < pc.light_count; ++i) {
    vec3 to_light;
    vec3 radiance = light_radiance(lights[i], in_world, to_light);
    float sin_tl = sqrt(max(1.0 - dot(t, to_light) * dot(t, to_light), 0.0));
    lit += radiance * sin_tl * light_transmittance(i, in_world);
  }
  float a = in_color_opacity.a;
  out_color = vec4(a * (in_fog.rgb + in_fog.a * in_color_opacity.rgb * lit), a);  // premultiplied
}
