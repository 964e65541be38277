#version 460
// AVSM resolve: per light texel, stream the texel's capture list through the
// AVSM core (shaders/avsm/avsm_core.glsl) — clear to (far, 1), composite each
// segment, compress to N nodes by the smallest-area rule — and store the N nodes
// packed in level 0 of the light's map (layout: shaders/shared/map_layouts.h).
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#define AVSM_CAPTURE_BINDING 0
#include "common/capture_lists.glsl"
#include "avsm/avsm_core.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 2) writeonly buffer Map { vec4 map_texels[]; };
#include "avsm/avsm_map.glsl"

#include "shared/passes/shadows/techniques/map_build.h"

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.resolution)))) return;
  int n = int(pc.count);
  AvsmCurve curve = avsm_clear(pc.far_depth);
  // The subgroup walks its lists in step (a lane whose list has ended idles) rather
  // than each lane leaving the loop on its own: with lists of very different lengths
  // (hair: a thousand segments next to one), lavapipe corrupted the long lists' curves
  // in the divergent version.
  uint node = imageLoad(capture_heads, texel).r;
  while (subgroupAny(node != kListEnd)) {
    if (node != kListEnd) {
      CaptureSegment s = capture_nodes[node];
      avsm_insert_segment(curve, s.entry, s.exit_depth, s.exit_trans, n);
      node = s.next;
    }
  }
  avsm_map_store(avsm_map_texel_base(pc.resolution, uint(n), 0u, uint(texel.x), uint(texel.y)), curve, n, pc.near_depth,
                 pc.far_depth);
}
