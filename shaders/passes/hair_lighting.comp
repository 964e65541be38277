#version 460
// Per-vertex hair lighting and fog, fast path: the fog from the cached march
// (common/volume_cached_march.glsl). See common/hair_lighting.glsl.
#extension GL_GOOGLE_include_directive : require

#define AVSM_VOLUME_BINDING_NANOVDB 8
#define AVSM_VOLUME_BINDING_MAJORANTS 9
#define AVSM_VOLUME_BINDING_PARAMETERS 10
#define AVSM_VOLUME_BINDING_ATLAS 11
#define AVSM_CACHE_BINDING 13
#include "common/volume_cached_march.glsl"
#include "common/lights.glsl"
#define AVSM_SHADOW_BINDING 4
#include "common/shadow_lookup.glsl"
layout(std430, binding = 3) readonly buffer Lights { GpuLight lights[]; };
#include "common/hair_lighting.glsl"
