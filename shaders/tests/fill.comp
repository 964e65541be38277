#version 460
// values[i] = i * scale + offset, for the compute test.
#extension GL_GOOGLE_include_directive : require
#include "tests/test_common.glsl"
layout(local_size_x = 64) in;
#include "tests/fill.h"
layout(std430, binding = 0) writeonly buffer Values { float values[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < pc.count) values[i] = affine(float(i), pc.scale, pc.offset);
}
