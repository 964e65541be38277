#version 460
// Opacity shadow map build (technique osm): per light texel, the optical depth in
// front of each of K planes evenly spaced over the light's caster range, from the
// texel's capture list (shaders/techniques/opacity_maps.glsl). K floats per texel.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#define AVSM_CAPTURE_BINDING 0
#include "common/capture_lists.glsl"
#include "techniques/opacity_maps.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 2) writeonly buffer Map { vec4 map_texels[]; };

#include "shared/passes/map_build.h"

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.resolution)))) return;
  int planes = int(pc.count);
  float tau[64];
  for (int k = 0; k < 64; ++k) tau[k] = 0.0;  // constant bounds throughout: see avsm_core.glsl
  float scale = 1.0 / max(pc.far_depth - pc.near_depth, 1e-20);
  // Lists walked in step across the subgroup (see avsm_resolve.comp).
  uint node = imageLoad(capture_heads, texel).r;
  while (subgroupAny(node != kListEnd)) {
    if (node != kListEnd) {
      CaptureSegment s = capture_nodes[node];
      node = s.next;
      float z0 = (s.entry - pc.near_depth) * scale, z1 = (s.exit_depth - pc.near_depth) * scale;
      float optical_depth = opacity_segment_optical_depth(s.exit_trans);
      // Planes in front of the segment get nothing: start at the first plane behind its entry.
      int first_plane = max(int(ceil(z0 * float(planes))), 1);
      for (int k = 1; k <= 64; ++k) {
        if (k > planes) break;
        if (k >= first_plane) tau[k - 1] += osm_plane_optical_depth(z0, z1, optical_depth, k, planes);
      }
    }
  }
  uint base = (uint(texel.y) * pc.resolution + uint(texel.x)) * uint(planes / 4);
  for (int g = 0; g < 16; ++g) {
    if (g >= planes / 4) break;
    map_texels[base + uint(g)] = vec4(tau[4 * g], tau[4 * g + 1], tau[4 * g + 2], tau[4 * g + 3]);
  }
}
