#version 460
// Fourier opacity map build (technique fom): per light texel, the K-term Fourier
// series of the extinction density over the light's caster range, from the
// texel's capture list (shaders/techniques/opacity_maps.glsl). Stored as pairs
// (a_k, b_k), k = 0..K-1 (b_0 = 0): 2K floats per texel.
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
  int terms = int(pc.count);
  float a[32], b[32];
  for (int k = 0; k < 32; ++k) a[k] = b[k] = 0.0;  // constant bounds throughout: see avsm_core.glsl
  float scale = 1.0 / max(pc.far_depth - pc.near_depth, 1e-20);
  // Lists walked in step across the subgroup (see avsm_resolve.comp).
  uint node = imageLoad(capture_heads, texel).r;
  while (subgroupAny(node != kListEnd)) {
    if (node != kListEnd) {
      CaptureSegment s = capture_nodes[node];
      node = s.next;
      float z0 = clamp((s.entry - pc.near_depth) * scale, 0.0, 1.0);
      float z1 = clamp((s.exit_depth - pc.near_depth) * scale, 0.0, 1.0);
      float optical_depth = opacity_segment_optical_depth(s.exit_trans);
      for (int k = 0; k < 32; ++k) {
        if (k >= terms) break;
        a[k] += fom_cosine_coefficient(z0, z1, optical_depth, k);
        if (k > 0) b[k] += fom_sine_coefficient(z0, z1, optical_depth, k);
      }
    }
  }
  uint base = (uint(texel.y) * pc.resolution + uint(texel.x)) * uint(terms / 2);
  for (int k = 0; k < 32; k += 2) {
    if (k >= terms) break;
    map_texels[base + uint(k / 2)] = vec4(a[k], b[k], a[k + 1], b[k + 1]);
  }
}
