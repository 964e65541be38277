#version 460
// A compute workload of known relative cost: each invocation runs `iterations`
// dependent steps. Used to calibrate timestamps and in the timing tests.
layout(local_size_x = 64) in;

#extension GL_GOOGLE_include_directive : require
#include "shared/gpu/spin.h"

layout(std430, binding = 0) buffer Values { float values[]; };

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.count) return;
  float x = float(i) * 0.001;
  for (uint k = 0u; k < pc.iterations; ++k) x = fract(x * 1.6180339 + 0.3141592);
  values[i] = x;
}
