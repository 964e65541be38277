#version 460
// The fixed-memory AVSM build for hosts that pass no density atlas: smoke from NanoVDB
// (common/avsm_fixed_build.glsl).
#extension GL_GOOGLE_include_directive : require
#define AVSM_FIXED_BUILD_NANOVDB
#include "common/avsm_fixed_build.glsl"
