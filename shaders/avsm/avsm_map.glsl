// Storing AVSM curves in a light's map (layout: shared/map_layouts.h): N/4
// vec4 per texel, one packed word per node (16-bit depth over the map's depth range,
// 16-bit transmittance), the last node repeated into unused slots. The includer
// declares `vec4 map_texels[]`.
#ifndef AVSM_MAP_GLSL
#define AVSM_MAP_GLSL
#include "shared/map_layouts.h"
#define AVSM_MAX_GROUPS 4

void avsm_map_store(uint base, AvsmCurve c, int n, float near_depth, float far_depth) {
  // Walk the nodes with the loop counter as the index (the same in every lane) and
  // hold the last real node for the padding: lavapipe mis-read local arrays indexed
  // by a per-lane value here (min(i, count - 1)), storing other lanes' nodes.
  uint node = avsm_node_pack(c.depth[0], c.trans[0], near_depth, far_depth);
  for (int g = 0; g < AVSM_MAX_GROUPS; ++g) {
    if (g >= n / 4) break;
    uvec4 nodes;
    for (int k = 0; k < 4; ++k) {
      int i = 4 * g + k;
      if (i < c.count) node = avsm_node_pack(c.depth[i], c.trans[i], near_depth, far_depth);
      nodes[k] = node;
    }
    map_texels[base + uint(g)] = uintBitsToFloat(nodes);
  }
}

#endif
