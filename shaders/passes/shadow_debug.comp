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
#include "shared/passes/shadow_debug.h"

// Below this a node counts as opaque (opaque segments end at exactly 0).
const float kOpaque = 1e-4;

// Depth where the first opaque blocker starts: for AVSM the node before the first
// node at ~0 transmittance, for the exact lists the smallest entry of a segment
// ending at 0; the far depth when there is none.
float first_opaque_depth(GpuShadow s, ivec2 texel) {
  float far_depth = s.texel_camera.z;
  if (s.technique == kShadowUncompressed) {
    float nearest = far_depth;
    uint previous = 0xffffffffu;
    for (uint node = shadow_list_head(s.slot, texel); node < previous;
         node = shadow_list_node(s.slot, node).next) {
      CaptureSegment n = shadow_list_node(s.slot, node);
      if (n.exit_trans <= kOpaque) nearest = min(nearest, n.entry);
      previous = node;
    }
    return nearest;
  }
  if (s.technique != kShadowAvsm) {
    // Opacity and Fourier maps keep no nodes: step along the depth range to where
    // the curve turns dark.
    const int kSteps = 128;
    float previous_depth = s.depth_range.x;
    for (int i = 1; i <= kSteps; ++i) {
      float depth = mix(s.depth_range.x, s.depth_range.y, float(i) / float(kSteps));
      if (shadow_texel_transmittance(s, 0u, texel, depth) <= 0.01) return previous_depth;
      previous_depth = depth;
    }
    return far_depth;
  }
  uint base = avsm_texel_base(s, 0u, texel);
  uint groups = s.node_count / 4u;
  float previous_depth = far_depth;
  for (uint i = 0u; i < s.node_count; ++i) {
    float depth = shadow_map_texel(s.slot, base + i / 4u)[i % 4u];
    float trans = shadow_map_texel(s.slot, base + groups + i / 4u)[i % 4u];
    if (trans <= kOpaque) return i == 0u ? depth : previous_depth;
    previous_depth = depth;
  }
  return far_depth;
}

void main() {
  GpuShadow s = shadows[pc.light];
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(s.resolution)))) return;
  float t = shadow_texel_transmittance(s, 0u, texel, first_opaque_depth(s, texel));
  // Row 0 of the map is the light's -y side; flip so the picture is upright.
  imageStore(debug_image, ivec2(texel.x, int(s.resolution) - 1 - texel.y), vec4(vec3(t), 1.0));
}
