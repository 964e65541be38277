#version 460
// Opaque meshes seen from a light, depth only: the nearest opaque caster per light
// texel, for the fixed-memory AVSM build (passes/light_depth_pass.h).
#extension GL_GOOGLE_include_directive : require
#include "shared/mesh.h"
#include "shared/passes/light_depth.h"

layout(std430, binding = 0) readonly buffer Vertices { CasterVertex vertices[]; };

void main() {
  CasterVertex v = vertices[gl_VertexIndex];
  gl_Position = pc.light_from_world * vec4(v.position[0], v.position[1], v.position[2], 1.0);
}
