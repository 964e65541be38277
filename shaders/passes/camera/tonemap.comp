#version 460
// Linear HDR -> display: ACES-like filmic curve (Narkowicz fit), sRGB encoding is
// done by the 8-bit sRGB target format.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba16f) uniform readonly image2D hdr;
layout(binding = 1, rgba8) uniform writeonly image2D ldr;
#extension GL_GOOGLE_include_directive : require
#include "shared/passes/camera/tonemap.h"

vec3 filmic(vec3 x) {
  return clamp((x * (2.51 * x + 0.03)) / (x * (2.43 * x + 0.59) + 0.14), 0.0, 1.0);
}

void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(p, imageSize(hdr)))) return;
  vec3 c = imageLoad(hdr, p).rgb * pc.exposure;
  vec3 mapped = filmic(c);
  // Encode to sRGB here: storage images cannot be sRGB formats.
  vec3 srgb = mix(mapped * 12.92, 1.055 * pow(mapped, vec3(1.0 / 2.4)) - 0.055, step(0.0031308, mapped));
  imageStore(ldr, p, vec4(srgb, 1.0));
}
