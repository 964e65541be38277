#version 460
// Fourier opacity map build (technique fom): per light texel, the K-term Fourier
// series of the extinction density over the light's caster range, from the
// texel's capture list (passes/shadows/techniques/opacity_maps.glsl). Stored as pairs
// (a_k, b_k), k = 0..K-1 (b_0 = 0): 2K floats per texel.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#define AVSM_CAPTURE_BINDING 0
#include "common/capture_lists.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 2) writeonly buffer Map { vec4 map_texels[]; };
#include "techniques/fom/fom_terms.glsl"

#include "shared/passes/shadows/techniques/map_build.h"

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.resolution)))) return;
  int terms = int(pc.count);
  fom_clear();
  // Lists walked in step across the subgroup (see avsm_resolve.comp).
  uint node = imageLoad(capture_heads, texel).r;
  while (subgroupAny(node != kListEnd)) {
    if (node != kListEnd) {
      CaptureSegment s = capture_nodes[node];
      node = s.next;
      fom_add_segment(s.entry, s.exit_depth, s.exit_trans, terms, pc.near_depth, pc.far_depth);
    }
  }
  fom_store(uint(texel.y) * pc.resolution + uint(texel.x), terms);
}
