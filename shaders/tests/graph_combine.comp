#version 460
// out = (a + b) / 2 + drawn / 2: reads two storage images and one sampled image.
layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba16f) uniform readonly image2D a;
layout(binding = 1, rgba16f) uniform readonly image2D b;
layout(binding = 2) uniform sampler2D drawn;
layout(binding = 3, rgba16f) uniform writeonly image2D result;
void main() {
  ivec2 p = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(result);
  if (p.x >= size.x || p.y >= size.y) return;
  vec4 d = texelFetch(drawn, p, 0);
  imageStore(result, p, 0.5 * (imageLoad(a, p) + imageLoad(b, p)) + 0.5 * d);
}
