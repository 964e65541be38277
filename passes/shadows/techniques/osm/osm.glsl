// Opacity shadow map lookups (K floats of optical depth per texel, osm_build.comp).
#ifndef AVSM_TECHNIQUE_OSM_GLSL
#define AVSM_TECHNIQUE_OSM_GLSL

#include "techniques/opacity_maps.glsl"

// Opacity shadow map texel: the optical depth at the planes around d, interpolated.
float osm_lookup(GpuShadow s, uint level, ivec2 texel, float d) {
  int planes = int(s.node_count);
  uint base = (uint(texel.y) * s.resolution + uint(texel.x)) * uint(planes / 4);
  float z = clamp((d - s.depth_range.z - s.depth_range.x) / max(s.depth_range.y - s.depth_range.x, 1e-20), 0.0, 1.0);
  int plane = int(floor(z * float(planes)));  // the plane in front of d (0: the near plane, no depth)
  float before = plane == 0 ? 0.0 : shadow_map_texel(s, base + uint(plane - 1) / 4u)[(plane - 1) % 4];
  int next = min(plane, planes - 1);
  float after = shadow_map_texel(s, base + uint(next) / 4u)[next % 4];
  return osm_transmittance(before, after, z, planes);
}

#endif
