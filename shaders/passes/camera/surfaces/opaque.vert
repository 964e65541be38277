#version 460
// Opaque meshes: vertices pulled from a storage buffer (world space).
#extension GL_GOOGLE_include_directive : require
#include "shared/mesh.h"
#include "shared/passes/camera/surfaces/opaque.h"

layout(std430, binding = 0) readonly buffer Vertices { CasterVertex vertices[]; };
layout(std430, binding = 12) readonly buffer Tangents { vec4 tangents[]; };  // parallel to Vertices

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;
layout(location = 3) out vec4 out_tangent;

void main() {
  CasterVertex v = vertices[gl_VertexIndex];
  out_world = vec3(v.position[0], v.position[1], v.position[2]);
  out_normal = vec3(v.normal[0], v.normal[1], v.normal[2]);
  out_uv = vec2(v.uv[0], v.uv[1]);
  out_tangent = tangents[gl_VertexIndex];
  gl_Position = pc.view_projection * vec4(out_world, 1.0);
}
