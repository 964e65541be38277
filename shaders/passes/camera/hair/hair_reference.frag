#version 460
// Hair fragments, reference path: the fibre lighting (common/fibre_light.glsl) with
// every light's shadow lookup per fragment, seen through the smoke in front of the
// strand as in hair.frag.
#extension GL_GOOGLE_include_directive : require
#include "common/lights.glsl"
#define AVSM_SHADOW_BINDING 4
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 15  // hair fragments ask for the pages they read
#include "common/shadow_lookup.glsl"

layout(std430, binding = 3) readonly buffer Lights { GpuLight lights[]; };
#include "common/fibre_light.glsl"
#include "shared/passes/camera/hair/hair.h"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec3 in_tangent;
layout(location = 2) flat in vec4 in_color_opacity;
layout(location = 4) in vec4 in_fog;
layout(location = 0) out vec4 out_color;

void main() {
  vec3 lit = fibre_light(in_world, normalize(in_tangent), pc.light_count);
  float a = in_color_opacity.a;
  out_color = vec4(a * (in_fog.rgb + in_fog.a * in_color_opacity.rgb * lit), a);  // premultiplied
}
