#version 460
// Its push constants lay out differently in C++ (see misaligned.h).
#extension GL_GOOGLE_include_directive : require
#include "tests/misaligned.h"
layout(local_size_x = 1) in;
layout(std430, binding = 0) writeonly buffer Values { float values[]; };
void main() { values[0] = pc.scale * pc.direction.x; }
