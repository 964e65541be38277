#version 460
// The fixed-memory AVSM build, smoke density from the brick atlas (common/avsm_fixed_build.glsl).
#extension GL_GOOGLE_include_directive : require
#include "common/avsm_fixed_build.glsl"
