#version 460
// Spreads a buffer over an image, tinted.
layout(local_size_x = 8, local_size_y = 8) in;
layout(push_constant) uniform Push { vec4 tint; uint width; uint height; } pc;
layout(std430, binding = 0) readonly buffer Values { float values[]; };
layout(binding = 1, rgba16f) uniform writeonly image2D target;
void main() {
  uvec2 p = gl_GlobalInvocationID.xy;
  if (p.x >= pc.width || p.y >= pc.height) return;
  imageStore(target, ivec2(p), vec4(values[p.y * pc.width + p.x] * pc.tint.rgb, 1.0));
}
