#version 460
// One AVSM mip level from the one above: per texel, avsm_mip_merge of its 2x2
// children (clamped at odd edges): their mean transmittance at every child node
// depth, re-compressed to N nodes. Levels sit one after another in the light's map.
#extension GL_GOOGLE_include_directive : require
#include "avsm/avsm_core.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 0) buffer AvsmMap { vec4 map_texels[]; };
#include "avsm/avsm_map.glsl"

#include "shared/passes/avsm_mips.h"

AvsmCurve load_curve(ivec2 texel, int n) {
  uint base = pc.source_offset + (uint(texel.y) * pc.source_size + uint(texel.x)) * uint(n / 2);
  AvsmCurve c = avsm_clear(0.0f);
  for (int g = 0; g < n / 4; ++g) {
    vec4 depths = map_texels[base + uint(g)];
    vec4 trans = map_texels[base + uint(n / 4 + g)];
    for (int k = 0; k < 4; ++k) {
      c.depth[4 * g + k] = depths[k];
      c.trans[4 * g + k] = trans[k];
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
  avsm_map_store(pc.target_offset + (uint(texel.y) * pc.target_size + uint(texel.x)) * uint(n / 2), merged, n);
}
