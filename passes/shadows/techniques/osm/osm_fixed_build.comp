#version 460
// Opacity shadow maps built straight from the casters (common/fixed_build.glsl), as
// Kim & Neumann build them: every segment adds its optical depth to the planes behind it.
#extension GL_GOOGLE_include_directive : require
#include "common/fixed_build.glsl"
#include "techniques/osm/osm_planes.glsl"

void fixed_clear() { osm_clear(); }

void fixed_take(float entry_depth, float exit_depth, float transmittance) {
  osm_add_segment(entry_depth, exit_depth, transmittance, int(fixed_technique_size()), pc.near_depth, pc.facing_point.w);
}

void fixed_store(uint texel_index) { osm_store(texel_index, int(fixed_technique_size())); }
