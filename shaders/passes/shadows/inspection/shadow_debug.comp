#version 460
// A light's transmittance map as a picture: per level-0 texel, the transmittance
// that reaches the first opaque surface along the texel's ray (or, with none, the
// far end), grey 0 (dark) to 1 (fully lit). Shadows of smoke, hair and meshes
// show on the surfaces they fall on. What avsm-capture writes as
// light<i>_transmittance.png.
#extension GL_GOOGLE_include_directive : require
#define AVSM_SHADOW_BINDING 1
#include "common/shadow_lookup.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 0, rgba8) uniform writeonly image2D debug_image;
#include "shared/passes/shadows/inspection/shadow_debug.h"

// Where the first opaque blocker along a texel's ray starts, for techniques that keep
// no nodes (opacity and Fourier maps): step along the depth range to where the curve
// turns dark; the far depth when it never does.
float shadow_stepped_first_opaque_depth(GpuShadow s, ivec2 texel) {
  const int kSteps = 128;
  float previous_depth = s.depth_range.x;
  for (int i = 1; i <= kSteps; ++i) {
    float depth = mix(s.depth_range.x, s.depth_range.y, float(i) / float(kSteps));
    if (shadow_texel_transmittance(s, 0u, texel, depth) <= 0.01) return previous_depth;
    previous_depth = depth;
  }
  return s.texel_camera.z;
}

// shadow_first_opaque_depth(s, texel): the technique's own answer where it has one
// (AVSM: the node before the first opaque node; the exact lists: the nearest opaque
// segment), else the stepped one above.
#include "techniques_first_opaque.glsl"

// A tint per level of a paged map, so the picture shows which levels are resident.
vec3 level_tint(uint level) {
  const vec3 tints[4] = vec3[4](vec3(1.0, 0.55, 0.45), vec3(0.5, 0.85, 0.45), vec3(0.45, 0.6, 1.0), vec3(1.0, 0.9, 0.4));
  return tints[level % 4u];
}

// A paged map's picture: the virtual map at the image's size, through the finest
// resident page at or above that level, tinted by its level, page edges darker.
void paged_picture(GpuShadow s, ivec2 pixel, int size) {
  vec2 uv = (vec2(pixel) + 0.5) / float(size);
  uint level = 0u;
  while (level + 1u < s.mip_count && (s.resolution >> level) > uint(size)) level += 1u;
  level = shadow_paged_resident_level(s, uv, level, false);
  ivec2 texel = ivec2(uv * float(max(s.resolution >> level, 1u)));
  GpuShadow page;
  ivec2 page_texel;
  vec3 color = vec3(1.0, 0.0, 1.0);  // no page: never, the coarsest level is always resident
  if (shadow_page_texel(s, level, texel, page, page_texel)) {
    float t = shadow_texel_transmittance(page, 0u, page_texel, shadow_first_opaque_depth(page, page_texel));
    bool edge = any(equal(page_texel, ivec2(0)));
    color = vec3(t) * mix(vec3(1.0), level_tint(level), 0.35) * (edge ? 0.7 : 1.0);
  }
  imageStore(debug_image, ivec2(pixel.x, size - 1 - pixel.y), vec4(color, 1.0));
}

// An area light's shared map as a grid of its virtual lights' maps, row by row from the
// bottom left (each a range of the map's texels: passes/shadows/light_view.h).
void virtual_lights_picture(GpuShadow s, ivec2 pixel) {
  uint tile = shadows[s.first_view].resolution, per_side = s.resolution / tile;
  uvec2 place = uvec2(pixel) / tile;
  uint k = place.y * per_side + place.x;
  vec3 color = vec3(0.0);
  if (place.x < per_side && k < s.view_count) {
    GpuShadow v = shadows[s.first_view + k];
    ivec2 texel = ivec2(uvec2(pixel) % tile);
    color = vec3(shadow_texel_transmittance(v, 0u, texel, shadow_first_opaque_depth(v, texel)));
  }
  imageStore(debug_image, ivec2(pixel.x, int(s.resolution) - 1 - pixel.y), vec4(color, 1.0));
}

void main() {
  GpuShadow s = shadows[pc.light];
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (s.views == kViewsVirtualLights) {
    if (all(lessThan(uvec2(texel), uvec2(s.resolution)))) virtual_lights_picture(s, texel);
    return;
  }
  if (shadow_is_paged(s)) {
    int size = imageSize(debug_image).x;
    if (all(lessThan(texel, ivec2(size)))) paged_picture(s, texel, size);
    return;
  }
  if (any(greaterThanEqual(uvec2(texel), uvec2(s.resolution)))) return;
  float t = shadow_texel_transmittance(s, 0u, texel, shadow_first_opaque_depth(s, texel));
  // Row 0 of the map is the light's -y side; flip so the picture is upright.
  imageStore(debug_image, ivec2(texel.x, int(s.resolution) - 1 - texel.y), vec4(vec3(t), 1.0));
}
