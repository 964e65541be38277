#version 460
// Every hair fragment a light sees (the ribbons of capture_hair.vert, built
// facing the light) becomes a short segment with the strand's opacity: the
// transmittance of one strand crossing.
#extension GL_GOOGLE_include_directive : require
#define AVSM_CAPTURE_APPEND
#define AVSM_CAPTURE_BINDING 3
#include "common/capture_lists.glsl"

// As in capture_hair.vert.
#include "shared/passes/shadows/capture/capture_hair.h"

layout(location = 0) in vec3 in_world;
layout(location = 2) flat in vec4 in_color_opacity;

void main() {
  float depth = dot(pc.depth_plane.xyz, in_world) + pc.depth_plane.w;
  float thickness = pc.texel_size.x + pc.texel_size.y * depth;
  capture_append(ivec2(gl_FragCoord.xy) - pc.raster_origin, pc.list_tile, depth, depth + thickness, 1.0 - clamp(in_color_opacity.a, 0.0, 1.0));
}
