#version 460
// The fast upsample and finish (shaders/passes/volume_upsample.glsl), with shadow-map lookups for volumes
// whose lighting cache is off.
#extension GL_GOOGLE_include_directive : require
#define AVSM_MARCH_MAP_LOOKUPS
#include "passes/volume_upsample.glsl"
