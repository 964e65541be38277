// Storing AVSM curves in a light's map (layout: shared/map_layouts.h):
// N/4 vec4 of depths then N/4 vec4 of transmittances per texel, the last node
// repeated into unused slots. The includer declares `vec4 map_texels[]`.
#ifndef AVSM_MAP_GLSL
#define AVSM_MAP_GLSL
#define AVSM_MAX_GROUPS 4

void avsm_map_store(uint base, AvsmCurve c, int n) {
  // Walk the nodes with the loop counter as the index (the same in every lane) and
  // hold the last real node for the padding: lavapipe mis-read local arrays indexed
  // by a per-lane value here (min(i, count - 1)), storing other lanes' nodes.
  float depth = c.depth[0], trans = c.trans[0];
  for (int g = 0; g < AVSM_MAX_GROUPS; ++g) {
    if (g >= n / 4) break;
    vec4 depths, transmittances;
    for (int k = 0; k < 4; ++k) {
      int i = 4 * g + k;
      if (i < c.count) {
        depth = c.depth[i];
        trans = c.trans[i];
      }
      depths[k] = depth;
      transmittances[k] = trans;
    }
    map_texels[base + uint(g)] = depths;
    map_texels[base + uint(n / 4 + g)] = transmittances;
  }
}

#endif
