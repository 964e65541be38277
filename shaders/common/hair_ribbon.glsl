// Hair strand segments as ribbons turned towards a point (the camera, or a light):
// one quad (6 vertices) per segment. Shared by hair.vert and capture_hair.vert; the
// geometry itself is common/hair_geometry.glsl (shared with C++).
// The strand buffers (shared/hair.h) are at bindings AVSM_HAIR_BINDING (points, 0
// unless the includer defines it), + 1 (segments) and + 2 (strands).
#ifndef AVSM_HAIR_RIBBON_GLSL
#define AVSM_HAIR_RIBBON_GLSL

#extension GL_GOOGLE_include_directive : require
#include "shared/hair.h"
#include "common/hair_geometry.glsl"
#ifndef AVSM_HAIR_BINDING
#define AVSM_HAIR_BINDING 0
#endif
layout(std430, binding = AVSM_HAIR_BINDING) readonly buffer Points { vec4 points[]; };
layout(std430, binding = AVSM_HAIR_BINDING + 1) readonly buffer Segments { StrandSegment segments[]; };
layout(std430, binding = AVSM_HAIR_BINDING + 2) readonly buffer Strands { Strand strands[]; };

struct RibbonVertex {
  vec3 world;
  vec3 tangent;
  vec4 color_opacity;  // opacity scaled by the widening
  uint point;          // the strand vertex this corner sits at
};

// Vertex `vertex_index` of the ribbons: segment vertex_index / 6, its corner
// vertex_index % 6 (hair_ribbon_corner).
RibbonVertex hair_ribbon_vertex(uint vertex_index, mat4 view_projection, vec3 facing_point, vec2 viewport) {
  uint segment = vertex_index / 6u, corner = vertex_index % 6u;
  StrandSegment s = segments[segment];
  Strand strand = strands[s.strand];
  vec3 p0 = points[s.first_point].xyz, p1 = points[s.first_point + 1u].xyz;
  RibbonCorner c = hair_ribbon_corner(p0, p1, strand.width, strand.color_opacity.a, corner, view_projection,
                                      facing_point, viewport);
  RibbonVertex v;
  v.world = c.world;
  v.tangent = c.tangent;
  v.color_opacity = vec4(strand.color_opacity.rgb, c.opacity);
  v.point = s.first_point + hair_ribbon_corner_along(corner);
  return v;
}

#endif
