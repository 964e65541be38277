#version 460
// Smoke seen from a light, density from NanoVDB for casters without a brick atlas
// (common/capture_smoke.glsl).
#extension GL_GOOGLE_include_directive : require
#define AVSM_VOLUME_BINDING_NANOVDB 0
#define AVSM_VOLUME_BINDING_MAJORANTS 1
#define AVSM_VOLUME_BINDING_PARAMETERS 2
#define AVSM_CAPTURE_BINDING 5
#include "common/capture_smoke.glsl"
