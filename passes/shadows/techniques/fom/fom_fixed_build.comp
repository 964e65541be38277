#version 460
// Fourier opacity maps built straight from the casters (common/fixed_build.glsl), as
// Jansen & Bavoil build them: every segment adds its share of each term.
#extension GL_GOOGLE_include_directive : require
#include "common/fixed_build.glsl"
#include "techniques/fom/fom_terms.glsl"

void fixed_clear() { fom_clear(); }

void fixed_take(float entry_depth, float exit_depth, float transmittance) {
  fom_add_segment(entry_depth, exit_depth, transmittance, int(fixed_technique_size()), pc.near_depth, pc.facing_point.w);
}

void fixed_store(uint texel_index) { fom_store(texel_index, int(fixed_technique_size())); }
