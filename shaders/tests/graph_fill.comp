#version 460
// values[i] = a smooth pattern of i; the first pass of the frame-graph GPU test.
layout(local_size_x = 64) in;
#extension GL_GOOGLE_include_directive : require
#include "tests/graph_fill.h"
layout(std430, binding = 0) writeonly buffer Values { float values[]; };
void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i < pc.count) values[i] = 0.5 + 0.5 * sin(float(i) * pc.frequency + pc.phase);
}
