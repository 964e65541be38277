// One texel's Fourier opacity map terms while it is built, from the capture lists
// (fom_build.comp) or straight from the casters (fom_fixed_build.comp): the K-term
// series of the extinction density over the light's caster range [near, far]
// (techniques/opacity_maps.glsl). The includer declares `vec4 map_texels[]`.
#ifndef AVSM_FOM_TERMS_GLSL
#define AVSM_FOM_TERMS_GLSL
#include "techniques/opacity_maps.glsl"

// Every loop is unrolled over all 32 terms with the real condition inside, so the
// terms are registers (see osm_planes.glsl for what lavapipe did with them in memory).
#extension GL_EXT_control_flow_attributes : require
float fom_a[32], fom_b[32];

void fom_clear() {
  [[unroll]] for (int k = 0; k < 32; ++k) fom_a[k] = fom_b[k] = 0.0;
}

void fom_add_segment(float entry_depth, float exit_depth, float exit_trans, int terms, float near_depth,
                     float far_depth) {
  float scale = 1.0 / max(far_depth - near_depth, 1e-20);
  float z0 = clamp((entry_depth - near_depth) * scale, 0.0, 1.0);
  float z1 = clamp((exit_depth - near_depth) * scale, 0.0, 1.0);
  float optical_depth = opacity_segment_optical_depth(exit_trans);
  [[unroll]] for (int k = 0; k < 32; ++k) {
    if (k < terms) {
      fom_a[k] += fom_cosine_coefficient(z0, z1, optical_depth, k);
      if (k > 0) fom_b[k] += fom_sine_coefficient(z0, z1, optical_depth, k);
    }
  }
}

// Pairs (a_k, b_k), k = 0..K-1 (b_0 = 0): K/2 vec4 per texel.
void fom_store(uint texel_index, int terms) {
  uint base = texel_index * uint(terms / 2);
  [[unroll]] for (int k = 0; k < 32; k += 2)
    if (k < terms) map_texels[base + uint(k / 2)] = vec4(fom_a[k], fom_b[k], fom_a[k + 1], fom_b[k + 1]);
}

#endif
