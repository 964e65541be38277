#version 460
// The viewer's shadow level overlay: the tonemapped image with one light's receivers
// tinted by the level their surface lookup reads (shadow_resolution.comp's results):
// level 0 red, then orange, yellow, green, cyan, blue, violet, magenta for the coarser
// ones, blended between two levels as trilinear lookups blend them. Pixels that are
// not the light's receivers are dimmed.
#extension GL_GOOGLE_include_directive : require
#include "shared/passes/camera/quality/shadow_level_overlay.h"
#include "shared/passes/camera/quality/shadow_resolution_results.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform image2D image;  // sRGB-encoded values (tonemap.comp)
layout(std430, binding = 1) readonly buffer Results { PixelShadowResolution results[]; };

const vec3 kLevelColours[kOverlayLevelColours] = vec3[](
    vec3(0.9, 0.1, 0.1), vec3(1.0, 0.55, 0.1), vec3(0.95, 0.9, 0.15), vec3(0.2, 0.8, 0.25),
    vec3(0.15, 0.8, 0.85), vec3(0.2, 0.35, 0.95), vec3(0.55, 0.25, 0.9), vec3(0.9, 0.25, 0.75));

vec3 level_colour(float level) {
  uint below = min(uint(floor(level)), kOverlayLevelColours - 1u);
  uint above = min(below + 1u, kOverlayLevelColours - 1u);
  return mix(kLevelColours[below], kLevelColours[above], fract(level));
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.image_size))) return;
  uint index = pc.light * pc.image_size.x * pc.image_size.y + uint(pixel.y) * pc.image_size.x + uint(pixel.x);
  float level = results[index].level;
  vec3 shown = imageLoad(image, pixel).rgb;
  shown = level < 0.0 ? 0.35 * shown : mix(shown, level_colour(level), 0.6);
  imageStore(image, pixel, vec4(shown, 1.0));
}
