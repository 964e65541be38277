// A hair segment's ribbon as a light's rasterizer sees it (the quad of
// common/hair_ribbon.glsl that capture_hair.vert draws facing the light), for the
// passes that cover light texels with it themselves: the hair binning and the
// fixed-memory AVSM build. The footprint, its coverage of a texel centre and its texel
// box are common/hair_geometry.glsl (shared with C++, so tests reproduce them); this
// reads the segment from the strand buffers.
#ifndef AVSM_HAIR_FOOTPRINT_GLSL
#define AVSM_HAIR_FOOTPRINT_GLSL
#extension GL_GOOGLE_include_directive : require
#include "common/hair_ribbon.glsl"

HairFootprint hair_footprint(uint segment, mat4 view_projection, vec3 facing_point, vec4 depth_plane,
                             float resolution) {
  StrandSegment s = segments[segment];
  Strand strand = strands[s.strand];
  return hair_footprint_of(points[s.first_point].xyz, points[s.first_point + 1u].xyz, strand.width,
                           strand.color_opacity.a, view_projection, facing_point, depth_plane, resolution);
}

#endif
