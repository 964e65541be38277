// Fourier opacity map lookups (K/2 vec4 of (a, b) pairs per texel, fom_build.comp).
#ifndef AVSM_TECHNIQUE_FOM_GLSL
#define AVSM_TECHNIQUE_FOM_GLSL

#include "techniques/opacity_maps.glsl"

// Fourier opacity map texel: the series' optical depth in front of d.
float fom_lookup(GpuShadow s, uint level, ivec2 texel, float d) {
  int terms = int(s.node_count);
  uint base = (uint(texel.y) * s.resolution + uint(texel.x)) * uint(terms / 2);
  float z = clamp((d - s.depth_range.z - s.depth_range.x) / max(s.depth_range.y - s.depth_range.x, 1e-20), 0.0, 1.0);
  float optical_depth = 0.0;
  for (int k = 0; k < 32; k += 2) {
    if (k >= terms) break;
    vec4 pair = shadow_map_texel(s, base + uint(k / 2));
    optical_depth +=
        fom_term_optical_depth(pair.x, pair.y, k, terms, z) + fom_term_optical_depth(pair.z, pair.w, k + 1, terms, z);
  }
  return fom_transmittance(optical_depth);
}

#endif
