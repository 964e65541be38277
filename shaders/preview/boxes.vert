#version 460
// Placeholder scene until scene loading lands: a floor and three boxes, generated
// from gl_VertexIndex (36 vertices per box), lit by one directional light.
layout(push_constant) uniform Push {
  mat4 view_projection;
  vec4 light_direction;  // xyz: direction the light travels
} pc;

layout(location = 0) out vec3 out_normal;
layout(location = 1) out vec3 out_albedo;

const vec3 kBoxCenter[4] = vec3[](vec3(0, -0.05, 0), vec3(-1.2, 0.5, 0), vec3(0.4, 0.35, 1.4), vec3(1.2, 0.75, 0.6));
const vec3 kBoxHalf[4] = vec3[](vec3(4, 0.05, 4), vec3(0.5), vec3(0.35), vec3(0.3, 0.75, 0.3));
const vec3 kBoxAlbedo[4] = vec3[](vec3(0.7), vec3(0.8, 0.3, 0.2), vec3(0.2, 0.6, 0.3), vec3(0.25, 0.35, 0.8));

void main() {
  int box = gl_VertexIndex / 36, corner = gl_VertexIndex % 36;
  int face = corner / 6, vertex = corner % 6;
  const ivec2 kQuad[6] = ivec2[](ivec2(0, 0), ivec2(1, 0), ivec2(1, 1), ivec2(0, 0), ivec2(1, 1), ivec2(0, 1));
  int axis = face % 3;
  float side = face < 3 ? 1.0 : -1.0;
  vec3 normal = vec3(0);
  normal[axis] = side;
  vec2 uv = vec2(kQuad[vertex]) * 2.0 - 1.0;
  if (side < 0.0) uv.x = -uv.x;  // keep counter-clockwise winding on both sides
  vec3 p = normal;
  p[(axis + 1) % 3] = uv.x;
  p[(axis + 2) % 3] = uv.y;
  vec3 world = kBoxCenter[box] + p * kBoxHalf[box];
  gl_Position = pc.view_projection * vec4(world, 1.0);
  out_normal = normal;
  out_albedo = kBoxAlbedo[box];
}
