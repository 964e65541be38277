#version 460
// Opaque meshes seen from a light: positions, and the uv for alpha (the same vertex
// buffer as the camera pass).
#extension GL_GOOGLE_include_directive : require
#include "shared/mesh.h"
#include "shared/passes/shadows/capture/capture_opaque.h"

layout(std430, binding = 0) readonly buffer Vertices { CasterVertex vertices[]; };

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec2 out_uv;

void main() {
  CasterVertex v = vertices[gl_VertexIndex];
  out_world = vec3(v.position[0], v.position[1], v.position[2]);
  out_uv = vec2(v.uv[0], v.uv[1]);
  gl_Position = pc.light_from_world * vec4(out_world, 1.0);
}
