// One texel's Fourier opacity map terms while it is built, from the capture lists
// (fom_build.comp) or straight from the casters (fom_fixed_build.comp): the K-term
// series of the extinction density over the light's caster range [near, far]
// (techniques/opacity_maps.glsl). The includer declares `vec4 map_texels[]`.
#ifndef AVSM_FOM_TERMS_GLSL
#define AVSM_FOM_TERMS_GLSL
#include "techniques/opacity_maps.glsl"

// Constant bounds throughout: see avsm_core.glsl. In a build whose workgroup meets
// at barriers, FOM_TERMS_IN_WORKGROUP_MEMORY (see osm_planes.glsl).
#ifdef FOM_TERMS_IN_WORKGROUP_MEMORY
shared float fom_terms_of[64][64];  // [2 k: a_k, 2 k + 1: b_k][invocation]
#define FOM_A(k) fom_terms_of[2 * (k)][gl_LocalInvocationIndex]
#define FOM_B(k) fom_terms_of[2 * (k) + 1][gl_LocalInvocationIndex]
#else
float fom_a[32], fom_b[32];
#define FOM_A(k) fom_a[k]
#define FOM_B(k) fom_b[k]
#endif

void fom_clear() {
  for (int k = 0; k < 32; ++k) FOM_A(k) = FOM_B(k) = 0.0;
}

void fom_add_segment(float entry_depth, float exit_depth, float exit_trans, int terms, float near_depth,
                     float far_depth) {
  float scale = 1.0 / max(far_depth - near_depth, 1e-20);
  float z0 = clamp((entry_depth - near_depth) * scale, 0.0, 1.0);
  float z1 = clamp((exit_depth - near_depth) * scale, 0.0, 1.0);
  float optical_depth = opacity_segment_optical_depth(exit_trans);
  for (int k = 0; k < 32; ++k) {
    if (k >= terms) break;
    FOM_A(k) += fom_cosine_coefficient(z0, z1, optical_depth, k);
    if (k > 0) FOM_B(k) += fom_sine_coefficient(z0, z1, optical_depth, k);
  }
}

// Pairs (a_k, b_k), k = 0..K-1 (b_0 = 0): K/2 vec4 per texel.
void fom_store(uint texel_index, int terms) {
  uint base = texel_index * uint(terms / 2);
  for (int k = 0; k < 32; k += 2) {
    if (k >= terms) break;
    map_texels[base + uint(k / 2)] = vec4(FOM_A(k), FOM_B(k), FOM_A(k + 1), FOM_B(k + 1));
  }
}

#endif
