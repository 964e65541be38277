// One texel's opacity shadow map planes while it is built, from the capture lists
// (osm_build.comp) or straight from the casters (osm_fixed_build.comp): the optical
// depth in front of each of K planes over the light's caster range [near, far]
// (techniques/opacity_maps.glsl). The includer declares `vec4 map_texels[]`.
#ifndef AVSM_OSM_PLANES_GLSL
#define AVSM_OSM_PLANES_GLSL
#include "techniques/opacity_maps.glsl"

// Every loop is unrolled over all 64 planes with the real condition inside, so the
// planes are registers. In memory (a private array, or workgroup memory), lavapipe
// let lanes that had no segment to add store into their planes anyway inside the
// fixed build's divergent loops: NaNs, changing from run to run.
#extension GL_EXT_control_flow_attributes : require
float osm_tau[64];

void osm_clear() {
  [[unroll]] for (int k = 0; k < 64; ++k) osm_tau[k] = 0.0;
}

void osm_add_segment(float entry_depth, float exit_depth, float exit_trans, int planes, float near_depth,
                     float far_depth) {
  float scale = 1.0 / max(far_depth - near_depth, 1e-20);
  float z0 = (entry_depth - near_depth) * scale, z1 = (exit_depth - near_depth) * scale;
  float optical_depth = opacity_segment_optical_depth(exit_trans);
  // Planes in front of the segment get nothing: start at the first plane behind its entry.
  int first_plane = max(int(ceil(z0 * float(planes))), 1);
  [[unroll]] for (int k = 1; k <= 64; ++k)
    if (k <= planes && k >= first_plane) osm_tau[k - 1] += osm_plane_optical_depth(z0, z1, optical_depth, k, planes);
}

// K/4 vec4 per texel.
void osm_store(uint texel_index, int planes) {
  uint base = texel_index * uint(planes / 4);
  [[unroll]] for (int g = 0; g < 16; ++g)
    if (g < planes / 4) map_texels[base + uint(g)] = vec4(osm_tau[4 * g], osm_tau[4 * g + 1], osm_tau[4 * g + 2], osm_tau[4 * g + 3]);
}

#endif
