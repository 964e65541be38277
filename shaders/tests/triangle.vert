#version 460
// One triangle covering the left half of the target, corners from the vertex index.
layout(location = 0) out vec3 out_color;
void main() {
  const vec2 corners[3] = vec2[](vec2(-1.0, -1.0), vec2(0.0, -1.0), vec2(-1.0, 1.0));
  const vec3 colors[3] = vec3[](vec3(1, 0, 0), vec3(1, 0, 0), vec3(1, 0, 0));
  gl_Position = vec4(corners[gl_VertexIndex], 0.0, 1.0);
  out_color = colors[gl_VertexIndex];
}
