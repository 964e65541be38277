#version 460
// ImGui colours are display values already: the target is a UNORM (not sRGB) format.
layout(binding = 1) uniform sampler2D panel_texture;
layout(location = 0) in vec4 in_color;
layout(location = 1) in vec2 in_uv;
layout(location = 0) out vec4 out_color;

void main() { out_color = in_color * texture(panel_texture, in_uv); }
