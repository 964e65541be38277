#version 460
// Opaque meshes seen from a light: positions only (the same vertex buffer as the camera pass).
#extension GL_GOOGLE_include_directive : require
#include "shared/mesh.h"
#include "shared/passes/capture_opaque.h"

layout(std430, binding = 0) readonly buffer Vertices { CasterVertex vertices[]; };

layout(location = 0) out vec3 out_world;

void main() {
  CasterVertex v = vertices[gl_VertexIndex];
  out_world = vec3(v.position[0], v.position[1], v.position[2]);
  gl_Position = pc.light_from_world * vec4(out_world, 1.0);
}
