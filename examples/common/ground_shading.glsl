// The host examples' shading pass (examples/host_embed, host_raw): the ground plane y = 0
// seen from straight above, one pixel per ground point, lit by light 0 and shadowed by
// the engine's AVSM map. The including .comp declares where the lookup's buffers are
// (common/shadow_lookup.glsl's binding macros) and the image `ground_image`.
#extension GL_GOOGLE_include_directive : require
#include "common/shadow_lookup.glsl"
#include "ground_shading.h"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  ivec2 size = imageSize(ground_image);
  if (any(greaterThanEqual(pixel, size))) return;
  vec2 uv = (vec2(pixel) + 0.5) / vec2(size);
  vec3 p = vec3(pc.ground.x + uv.x * pc.ground.z, 0.0, pc.ground.y + uv.y * pc.ground.w);
  vec3 n = vec3(0.0, 1.0, 0.0);
  vec3 l = pc.to_light.w > 0.5 ? normalize(pc.to_light.xyz - p) : pc.to_light.xyz;
  float transmittance = surface_light_transmittance(0u, p, n, l);
  // A faint checker so the picture shows the ground's scale.
  ivec2 cell = ivec2(floor(p.xz * 2.0));
  vec3 albedo = ((cell.x + cell.y) & 1) == 0 ? vec3(0.8) : vec3(0.7);
  vec3 color = albedo * (0.08 + max(dot(n, l), 0.0) * transmittance);
  imageStore(ground_image, pixel, vec4(color, transmittance));  // alpha: the transmittance itself
}
