#version 460
// AVSM built straight from the casters (common/fixed_build.glsl): each texel's curve
// takes every segment by streaming insertion and compression (avsm/avsm_core.glsl).
// Built per node count (AVSM_NODES), so the curve stays in registers.
#extension GL_GOOGLE_include_directive : require
#include "avsm/avsm_core.glsl"
#include "common/fixed_build.glsl"
#include "avsm/avsm_map.glsl"

AvsmCurve curve;

void fixed_clear() { curve = avsm_clear(pc.facing_point.w); }

void fixed_take(float entry_depth, float exit_depth, float transmittance) {
  avsm_insert_segment(curve, entry_depth, exit_depth, transmittance, AVSM_NODES);
}

void fixed_store(uint texel_index) {
  avsm_map_store(texel_index * avsm_texel_vec4s(uint(AVSM_NODES)), curve, AVSM_NODES, pc.near_depth, pc.facing_point.w);
}
