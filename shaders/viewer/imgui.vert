#version 460
// Dear ImGui's vertices, pulled from a storage buffer (our pipelines have no vertex
// input state). ImDrawVert is 20 bytes: pos (2 floats), uv (2 floats), colour (RGBA8).
layout(std430, binding = 0) readonly buffer Vertices { float vertex_data[]; };
#extension GL_GOOGLE_include_directive : require
#include "shared/viewer/imgui.h"
layout(location = 0) out vec4 out_color;
layout(location = 1) out vec2 out_uv;

void main() {
  const uint base = uint(gl_VertexIndex) * 5u;  // gl_VertexIndex includes the draw's vertex offset
  const vec2 position = vec2(vertex_data[base], vertex_data[base + 1u]);
  out_uv = vec2(vertex_data[base + 2u], vertex_data[base + 3u]);
  out_color = unpackUnorm4x8(floatBitsToUint(vertex_data[base + 4u]));
  // ImGui's y points down, like Vulkan's framebuffer: no flip.
  gl_Position = vec4(position * pc.scale + pc.translate, 0.0, 1.0);
}
