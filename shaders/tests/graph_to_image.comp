#version 460
// Spreads a buffer over an image, tinted.
layout(local_size_x = 8, local_size_y = 8) in;
#extension GL_GOOGLE_include_directive : require
#include "tests/graph_to_image.h"
layout(std430, binding = 0) readonly buffer Values { float values[]; };
layout(binding = 1, rgba16f) uniform writeonly image2D target;
void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= pc.width || p.y >= pc.height) return;
  imageStore(target, ivec2(p), vec4(values[p.y * pc.width + p.x] * pc.tint.rgb, 1.0));
}
