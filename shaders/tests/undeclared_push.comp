#version 460
// Push constants declared in GLSL only, with no C++ declaration to check them against.
layout(local_size_x = 1) in;
layout(push_constant) uniform Push { float scale; } pc;
layout(std430, binding = 0) writeonly buffer Values { float values[]; };
void main() { values[0] = pc.scale; }
