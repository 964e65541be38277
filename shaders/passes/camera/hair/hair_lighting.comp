#version 460
// Per-vertex hair lighting and fog, fast path: the fog from the cached march
// (common/volume_cached_march.glsl). See common/hair_lighting.glsl.
#extension GL_GOOGLE_include_directive : require

#define AVSM_VOLUME_BINDING_NANOVDB 8
#define AVSM_VOLUME_BINDING_MAJORANTS 9
#define AVSM_VOLUME_BINDING_PARAMETERS 10
#define AVSM_VOLUME_BINDING_ATLAS 11
#define AVSM_CACHE_BINDING 13
#define AVSM_MARCH_LIGHTS_BINDING 3
#define AVSM_SHADOW_BINDING 4
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 15  // hair vertices (and the smoke before them) ask for pages
#define AVSM_MARCH_MAP_LOOKUPS  // the lights are needed anyway, and a vertex is one thread
#include "common/volume_cached_march.glsl"
#define AVSM_FOG_BINDING 16
#define AVSM_FOG_INTEGRATED_BINDING 17
#include "common/fog.glsl"
#include "common/hair_lighting.glsl"
