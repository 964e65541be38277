#version 460
// Shadow quality at hair receivers: per strand vertex (every `stride`-th) that the
// camera sees — inside the view and not behind the opaque depth — and per light,
// |T - T_ref| between the technique and the exact capture lists, looked up as the
// hair pass shades (light_transmittance at the fibre, no normal offset). -1 where a
// vertex is not a receiver. Hair-on-hair occlusion is not tested (hair writes no
// depth): every visible-to-the-opaque-depth vertex counts.
#extension GL_GOOGLE_include_directive : require
#define AVSM_SHADOW_BINDING 3
#include "common/shadow_lookup.glsl"

layout(local_size_x = 64) in;
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(binding = 1) uniform sampler2D depth_texture;
layout(std430, binding = 2) writeonly buffer Results { float results[]; };  // [light * receiver_count + receiver]

#include "shared/passes/camera/quality/shadow_quality_hair.h"

void main() {
  uint receiver = gl_GlobalInvocationID.x;
  if (receiver >= pc.receiver_count) return;
  vec3 p = points[receiver * pc.stride].xyz;
  vec4 clip = pc.view_projection * vec4(p, 1.0);
  bool seen = clip.w > 0.0 && all(lessThanEqual(abs(clip.xy), vec2(clip.w))) && clip.z >= 0.0 && clip.z <= clip.w;
  if (seen) {
    // The camera viewport is flipped (+y up): row 0 is the top of the image.
    vec2 ndc = clip.xy / clip.w;
    ivec2 pixel = clamp(ivec2((vec2(ndc.x, -ndc.y) * 0.5 + 0.5) * vec2(pc.image_size)), ivec2(0),
                        ivec2(pc.image_size) - 1);
    seen = clip.z / clip.w <= texelFetch(depth_texture, pixel, 0).r;
  }
  // Every light is looked up in every invocation (results discarded where not a
  // receiver): lookups in divergent branches misbehaved on lavapipe.
  for (uint light = 0u; light < pc.light_count; ++light) {
    float error = abs(light_transmittance(light, p) - reference_light_transmittance(light, p));
    results[light * pc.receiver_count + receiver] = seen ? error : -1.0;
  }
}
