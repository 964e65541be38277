#version 460
// Opaque meshes: vertices pulled from a storage buffer (world space).
struct Vertex { float px, py, pz, nx, ny, nz, u, v; };
layout(std430, binding = 0) readonly buffer Vertices { Vertex vertices[]; };
layout(push_constant) uniform Push {
  mat4 view_projection;
  vec4 camera_position;
  uint material;
  uint light_count;
} pc;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_normal;
layout(location = 2) out vec2 out_uv;

void main() {
  Vertex v = vertices[gl_VertexIndex];
  out_world = vec3(v.px, v.py, v.pz);
  out_normal = vec3(v.nx, v.ny, v.nz);
  out_uv = vec2(v.u, v.v);
  gl_Position = pc.view_projection * vec4(out_world, 1.0);
}
