#version 460
// Every mesh fragment a light sees becomes a short segment over one texel's world size
// behind the surface, taking transmittance to what the material lets through there:
// 0 for opaque and for masked texels at or above the cutoff (masked texels below it
// add nothing), 1 - alpha for blended ones (common/caster_alpha.glsl).
#extension GL_GOOGLE_include_directive : require
#define AVSM_CAPTURE_APPEND
#define AVSM_CAPTURE_BINDING 1
#include "common/capture_lists.glsl"

#include "shared/passes/shadows/capture/capture_opaque.h"
#define AVSM_CASTER_ALPHA_BINDING 4
#include "common/caster_alpha.glsl"

layout(location = 0) in vec3 in_world;
layout(location = 1) in vec2 in_uv;

void main() {
  float transmittance = caster_transmittance(in_uv);
  if (transmittance >= 1.0) return;  // a hole: nothing to append
  float depth = dot(pc.depth_plane.xyz, in_world) + pc.depth_plane.w;
  float thickness = pc.texel_size.x + pc.texel_size.y * depth;
  capture_append(ivec2(gl_FragCoord.xy) - pc.raster_origin, pc.list_tile, depth, depth + thickness, transmittance);
}
