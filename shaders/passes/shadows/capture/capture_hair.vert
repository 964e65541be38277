#version 460
// Hair ribbons facing the light (common/hair_ribbon.glsl), for capture_hair.frag.
#extension GL_GOOGLE_include_directive : require
#include "common/hair_ribbon.glsl"

#include "shared/passes/shadows/capture/capture_hair.h"

layout(location = 0) out vec3 out_world;
layout(location = 2) flat out vec4 out_color_opacity;

void main() {
  RibbonVertex v = hair_ribbon_vertex(uint(gl_VertexIndex), pc.view_projection, pc.facing_point.xyz, pc.viewport);
  out_world = v.world;
  out_color_opacity = v.color_opacity;
  gl_Position = pc.view_projection * vec4(v.world, 1.0);
}
