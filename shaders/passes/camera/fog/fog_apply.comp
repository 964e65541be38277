#version 460
// The fog over the opaque colour (passes/camera/fog/fog_apply_pass.h), fast: each pixel's
// surface (or the background, at the fog's far end) seen through the integrated grid,
// color = color x T + in-scattered.
#extension GL_GOOGLE_include_directive : require

#define AVSM_FOG_BINDING 2
#define AVSM_FOG_INTEGRATED_BINDING 3
#include "common/fog.glsl"
#include "shared/passes/camera/fog/fog.h"
#include "passes/camera/fog/fog_rays.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba16f) uniform image2D color_image;
layout(binding = 1) uniform sampler2D depth_texture;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.output_size))) return;
  vec2 centre = vec2(pixel) + 0.5;
  vec4 fog = fog_towards(centre, fog_surface_distance(centre, texelFetch(depth_texture, pixel, 0).r));
  vec4 color = imageLoad(color_image, pixel);
  imageStore(color_image, pixel, vec4(color.rgb * fog.a + fog.rgb, color.a));
}
