#version 460
// A hand-kept copy of GpuLight (shared/lights.h) that has drifted: one member short.
layout(local_size_x = 1) in;
struct GpuLight {
  vec4 position_type;
  vec4 radiance;
};
layout(std430, binding = 0) readonly buffer Lights { GpuLight lights[]; };
layout(std430, binding = 1) writeonly buffer Values { float values[]; };
void main() { values[0] = lights[0].radiance.x; }
