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

void main() {
  GpuShadow s = shadows[pc.light];
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(s.resolution)))) return;
  float t = shadow_texel_transmittance(s, 0u, texel, shadow_first_opaque_depth(s, texel));
  // Row 0 of the map is the light's -y side; flip so the picture is upright.
  imageStore(debug_image, ivec2(texel.x, int(s.resolution) - 1 - texel.y), vec4(vec3(t), 1.0));
}
