#version 460
// Camera-facing hair ribbons (common/hair_ribbon.glsl). The lighting and fog of each
// segment's two vertices (hair_lighting.comp) are interpolated along it.
#extension GL_GOOGLE_include_directive : require
#include "common/hair_ribbon.glsl"

#include "shared/hair.h"
layout(std430, binding = 8) readonly buffer VertexLights { HairVertexLight vertex_lights[]; };
#include "shared/passes/camera/hair/hair.h"

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_tangent;
layout(location = 2) flat out vec4 out_color_opacity;
layout(location = 3) out vec3 out_lit;
layout(location = 4) out vec4 out_fog;

void main() {
  RibbonVertex v = hair_ribbon_vertex(uint(gl_VertexIndex), pc.view_projection, pc.camera_position.xyz, pc.viewport);
  HairVertexLight light = vertex_lights[v.point];
  out_world = v.world;
  out_tangent = v.tangent;
  out_color_opacity = v.color_opacity;
  out_lit = light.lit.rgb;
  out_fog = light.fog;
  gl_Position = pc.view_projection * vec4(v.world, 1.0);
}
