#version 460
// Opaque meshes seen from a light, depth only: the nearest opaque caster per light
// texel, for the fixed-memory AVSM build (passes/shadows/fixed_build/light_depth_pass.h). The uv is for
// the alpha-tested draws' fragment stage (light_depth.frag); depth-only draws ignore it.
#extension GL_GOOGLE_include_directive : require
#include "shared/mesh.h"
#include "shared/passes/shadows/fixed_build/light_depth.h"

layout(std430, binding = 0) readonly buffer Vertices { CasterVertex vertices[]; };

layout(location = 0) out vec2 out_uv;

void main() {
  CasterVertex v = vertices[gl_VertexIndex];
  out_uv = vec2(v.uv[0], v.uv[1]);
  gl_Position = pc.light_from_world * vec4(v.position[0], v.position[1], v.position[2], 1.0);
}
