#version 460
// Every opaque fragment a light sees becomes a short dense segment that takes
// transmittance to 0 over one texel's world size behind the surface.
#extension GL_GOOGLE_include_directive : require
#define AVSM_CAPTURE_APPEND
#define AVSM_CAPTURE_BINDING 1
#include "common/capture_lists.glsl"

#include "shared/passes/capture_opaque.h"

layout(location = 0) in vec3 in_world;

void main() {
  float depth = dot(pc.depth_plane.xyz, in_world) + pc.depth_plane.w;
  float thickness = pc.texel_size.x + pc.texel_size.y * depth;
  capture_append(ivec2(gl_FragCoord.xy), depth, depth + thickness, 0.0);
}
