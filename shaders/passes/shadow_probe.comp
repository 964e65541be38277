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
  {
    GpuShadow s = shadows[light];
    vec3 p = points[point].xyz;
    vec4 clip = s.light_from_world * vec4(p, 1.0);
    vec2 uv = clip.xy / clip.w * 0.5 + 0.5;
    ivec2 texel = clamp(ivec2(uv * float(s.resolution)), ivec2(0), ivec2(int(s.resolution) - 1));
    uint node = imageLoad(shadow_list_heads[s.slot], texel).r;
    float first_entry = node == 0xffffffffu ? -1.0 : shadow_list_nodes[s.slot].nodes[node].entry;
    float v = point == 0u ? shadow_light_depth(s, p) : point == 1u ? uv.x : point == 2u ? uv.y : point == 3u ? float(node) : point == 4u ? first_entry : float(s.technique);
    results[light * pc.point_count + point] = v;
  }
}
