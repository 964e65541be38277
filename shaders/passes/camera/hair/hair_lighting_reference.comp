#version 460
// Per-vertex hair fog, reference path: the fog from the reference march
// (common/volume_reference_march.glsl: NanoVDB, quarter-voxel steps, map lookups
// along the ray). See common/hair_lighting.glsl.
#extension GL_GOOGLE_include_directive : require

#define AVSM_VOLUME_BINDING_NANOVDB 8
#define AVSM_VOLUME_BINDING_MAJORANTS 9
#define AVSM_VOLUME_BINDING_PARAMETERS 10
#define AVSM_MARCH_LIGHTS_BINDING 3
#define AVSM_SHADOW_BINDING 4
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 15  // hair vertices (and the smoke before them) ask for pages
#include "common/volume_reference_march.glsl"
#define AVSM_FOG_BINDING 16
#define AVSM_FOG_INTEGRATED_BINDING 17
#include "common/fog.glsl"
#include "common/hair_lighting.glsl"
