#version 460
layout(push_constant) uniform Push {
  mat4 view_projection;
  vec4 light_direction;
} pc;
layout(location = 0) in vec3 in_normal;
layout(location = 1) in vec3 in_albedo;
layout(location = 0) out vec4 out_color;
void main() {
  float lambert = max(dot(normalize(in_normal), -normalize(pc.light_direction.xyz)), 0.0);
  vec3 sky = vec3(0.15, 0.18, 0.25);
  out_color = vec4(in_albedo * (sky + 1.6 * lambert), 1.0);
}
