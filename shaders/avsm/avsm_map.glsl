// Storing AVSM curves in a light's map (layout: shaders/common/shadow_lookup.glsl):
// N/4 vec4 of depths then N/4 vec4 of transmittances per texel, the last node
// repeated into unused slots. The includer declares `vec4 map_texels[]`.
#ifndef AVSM_MAP_GLSL
#define AVSM_MAP_GLSL

void avsm_map_store(uint base, AvsmCurve c, int n) {
  for (int g = 0; g < n / 4; ++g) {
    vec4 depths, trans;
    for (int k = 0; k < 4; ++k) {
      int i = min(4 * g + k, c.count - 1);
      depths[k] = c.depth[i];
      trans[k] = c.trans[i];
    }
    map_texels[base + uint(g)] = depths;
    map_texels[base + uint(n / 4 + g)] = trans;
  }
}

#endif
