// Hair strand segments as ribbons turned towards a point (the camera, or a light):
// one quad (6 vertices) per segment. Shared by hair.vert and capture_hair.vert.
// The strand buffers (shared/hair.h) are at bindings AVSM_HAIR_BINDING (points, 0
// unless the includer defines it), + 1 (segments) and + 2 (strands).
#ifndef AVSM_HAIR_RIBBON_GLSL
#define AVSM_HAIR_RIBBON_GLSL

#extension GL_GOOGLE_include_directive : require
#include "shared/hair.h"
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

// Ribbons are kept at least one pixel wide, their opacity scaled by the widening
// (coverage), so thin strands keep their weight instead of flickering.
RibbonVertex hair_ribbon_vertex(uint vertex_index, mat4 view_projection, vec3 facing_point, vec2 viewport) {
  uint segment = vertex_index / 6u, corner = vertex_index % 6u;
  StrandSegment s = segments[segment];
  Strand strand = strands[s.strand];
  vec3 p0 = points[s.first_point].xyz, p1 = points[s.first_point + 1u].xyz;
  const uint kAlong[6] = uint[](0, 1, 1, 0, 1, 0);
  const float kSide[6] = float[](-1, -1, 1, -1, 1, 1);
  vec3 p = kAlong[corner] == 0u ? p0 : p1;
  vec3 tangent = normalize(p1 - p0 + vec3(1e-9));
  vec3 to_facing = normalize(facing_point - p);
  vec3 side = normalize(cross(tangent, to_facing) + vec3(1e-9));

  vec4 clip_center = view_projection * vec4(p, 1.0);
  vec4 clip_offset = view_projection * vec4(p + side * strand.width, 1.0);
  vec2 pixels = abs(clip_offset.xy / clip_offset.w - clip_center.xy / clip_center.w) * 0.5 * viewport;
  float width_pixels = max(length(pixels), 1e-6);
  float widen = max(1.0, 1.0 / width_pixels);

  RibbonVertex v;
  v.world = p + side * (0.5 * strand.width * widen * kSide[corner]);
  v.tangent = tangent;
  v.color_opacity = vec4(strand.color_opacity.rgb, strand.color_opacity.a / widen);
  v.point = s.first_point + kAlong[corner];
  return v;
}

#endif
