#version 460
// Opaque meshes seen from a light: positions only (the same vertex buffer as the camera pass).
struct Vertex { float px, py, pz, nx, ny, nz, u, v; };
layout(std430, binding = 0) readonly buffer Vertices { Vertex vertices[]; };
// Mirrors CaptureOpaquePass's push constants (passes/capture_opaque_pass.cpp).
layout(push_constant) uniform Push {
  mat4 light_from_world;
  vec4 depth_plane;  // light depth(p) = dot(xyz, p) + w
  vec2 texel_size;   // world size of a texel at depth d: x + y * d
} pc;

layout(location = 0) out vec3 out_world;

void main() {
  Vertex v = vertices[gl_VertexIndex];
  out_world = vec3(v.px, v.py, v.pz);
  gl_Position = pc.light_from_world * vec4(out_world, 1.0);
}
