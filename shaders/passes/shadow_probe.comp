#version 460
// Transmittance probes: for every light and every world point, what the camera
// passes would get from light_transmittance() there (avsm-capture --probe).
#extension GL_GOOGLE_include_directive : require
#define AVSM_SHADOW_BINDING 2
#include "common/shadow_lookup.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) writeonly buffer Results { float results[]; };  // [light * point_count + point]
layout(push_constant) uniform Push {
  uint point_count;
  uint light_count;
} pc;

void main() {
  uint point = gl_GlobalInvocationID.x;
  if (point >= pc.point_count) return;
  for (uint light = 0u; light < pc.light_count; ++light)
    results[light * pc.point_count + point] = light_transmittance(light, points[point].xyz);
}
