#version 460
// One camera-facing ribbon quad (6 vertices) per strand segment.
struct Strand { vec4 color_opacity; float width; float pad0, pad1, pad2; };
layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) readonly buffer Segments { uvec2 segments[]; };  // (first point, strand)
layout(std430, binding = 2) readonly buffer Strands { Strand strands[]; };
layout(push_constant) uniform Push {
  mat4 view_projection;
  vec4 camera_position;
  vec2 viewport;
  uint light_count;
  float pad;
} pc;

layout(location = 0) out vec3 out_world;
layout(location = 1) out vec3 out_tangent;
layout(location = 2) flat out vec4 out_color_opacity;

void main() {
  uint segment = uint(gl_VertexIndex) / 6u, corner = uint(gl_VertexIndex) % 6u;
  uvec2 s = segments[segment];
  Strand strand = strands[s.y];
  vec3 p0 = points[s.x].xyz, p1 = points[s.x + 1u].xyz;
  const float kAlong[6] = float[](0, 1, 1, 0, 1, 0);
  const float kSide[6] = float[](-1, -1, 1, -1, 1, 1);
  vec3 p = mix(p0, p1, kAlong[corner]);
  vec3 tangent = normalize(p1 - p0 + vec3(1e-9));
  vec3 to_camera = normalize(pc.camera_position.xyz - p);
  vec3 side = normalize(cross(tangent, to_camera) + vec3(1e-9));

  // Keep ribbons at least one pixel wide; scale opacity by the widening (coverage).
  vec4 clip_center = pc.view_projection * vec4(p, 1.0);
  vec4 clip_offset = pc.view_projection * vec4(p + side * strand.width, 1.0);
  vec2 pixels = abs(clip_offset.xy / clip_offset.w - clip_center.xy / clip_center.w) * 0.5 * pc.viewport;
  float width_pixels = max(length(pixels), 1e-6);
  float widen = max(1.0, 1.0 / width_pixels);
  float opacity = strand.color_opacity.a / widen;

  out_world = p + side * (0.5 * strand.width * widen * kSide[corner]);
  out_tangent = tangent;
  out_color_opacity = vec4(strand.color_opacity.rgb, opacity);
  gl_Position = pc.view_projection * vec4(out_world, 1.0);
}
