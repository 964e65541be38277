#version 460
// One AVSM mip level from the one above: per texel, avsm_mip_merge of its 2x2
// children (clamped at odd edges), loaded from their stored (packed) nodes: their mean
// transmittance at every child node depth, re-compressed to N nodes and stored packed
// over the same depth range. Levels sit one after another in the light's map.
#extension GL_GOOGLE_include_directive : require
#include "avsm/avsm_core.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) buffer AvsmMap { vec4 map_texels[]; };
#include "avsm/avsm_map.glsl"

#include "shared/passes/shadows/techniques/avsm_mips.h"

// A stored curve, all N slots as nodes (the padding repeats the last node).
AvsmCurve load_curve(ivec2 texel, int n) {
  uint base = pc.source_offset + (uint(texel.y) * pc.source_size + uint(texel.x)) * avsm_texel_vec4s(uint(n));
  AvsmCurve c = avsm_clear(0.0f);
  for (int g = 0; g < n / 4; ++g) {
    uvec4 nodes = floatBitsToUint(map_texels[base + uint(g)]);
    for (int k = 0; k < 4; ++k) {
      c.depth[4 * g + k] = avsm_node_depth(nodes[k], pc.near_depth, pc.far_depth);
      c.trans[4 * g + k] = avsm_node_transmittance(nodes[k]);
    }
  }
  c.count = n;
  return c;
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.target_size)))) return;
  int n = int(pc.node_count);
  int last = int(pc.source_size) - 1;
  AvsmCurve merged = avsm_mip_merge(load_curve(min(2 * texel, ivec2(last)), n),
                                    load_curve(min(2 * texel + ivec2(1, 0), ivec2(last)), n),
                                    load_curve(min(2 * texel + ivec2(0, 1), ivec2(last)), n),
                                    load_curve(min(2 * texel + ivec2(1, 1), ivec2(last)), n), n);
  uint target = pc.target_offset + (uint(texel.y) * pc.target_size + uint(texel.x)) * avsm_texel_vec4s(uint(n));
  avsm_map_store(target, merged, n, pc.near_depth, pc.far_depth);
}
