// One texel's opacity shadow map planes while it is built, from the capture lists
// (osm_build.comp) or straight from the casters (osm_fixed_build.comp): the optical
// depth in front of each of K planes over the light's caster range [near, far]
// (techniques/opacity_maps.glsl). The includer declares `vec4 map_texels[]`.
#ifndef AVSM_OSM_PLANES_GLSL
#define AVSM_OSM_PLANES_GLSL
#include "techniques/opacity_maps.glsl"

// Constant bounds throughout: see avsm_core.glsl. A build whose workgroup meets at
// barriers (osm_fixed_build.comp) defines OSM_PLANES_IN_WORKGROUP_MEMORY: lavapipe
// garbled a 64-entry private array held across barriers (other invocations' values,
// changing from run to run).
#ifdef OSM_PLANES_IN_WORKGROUP_MEMORY
shared float osm_planes_of[64][64];  // [plane][invocation]
#define OSM_TAU(k) osm_planes_of[k][gl_LocalInvocationIndex]
#else
float osm_tau[64];
#define OSM_TAU(k) osm_tau[k]
#endif

void osm_clear() {
  for (int k = 0; k < 64; ++k) OSM_TAU(k) = 0.0;
}

void osm_add_segment(float entry_depth, float exit_depth, float exit_trans, int planes, float near_depth,
                     float far_depth) {
  float scale = 1.0 / max(far_depth - near_depth, 1e-20);
  float z0 = (entry_depth - near_depth) * scale, z1 = (exit_depth - near_depth) * scale;
  float optical_depth = opacity_segment_optical_depth(exit_trans);
  // Planes in front of the segment get nothing: start at the first plane behind its entry.
  int first_plane = max(int(ceil(z0 * float(planes))), 1);
  for (int k = 1; k <= 64; ++k) {
    if (k > planes) break;
    if (k >= first_plane) OSM_TAU(k - 1) += osm_plane_optical_depth(z0, z1, optical_depth, k, planes);
  }
}

// K/4 vec4 per texel.
void osm_store(uint texel_index, int planes) {
  uint base = texel_index * uint(planes / 4);
  for (int g = 0; g < 16; ++g) {
    if (g >= planes / 4) break;
    map_texels[base + uint(g)] = vec4(OSM_TAU(4 * g), OSM_TAU(4 * g + 1), OSM_TAU(4 * g + 2), OSM_TAU(4 * g + 3));
  }
}

#endif
