#version 460
// The fast camera march (shaders/passes/camera/volumes/volume_cached_march.glsl), with shadow-map lookups for volumes
// whose lighting cache is off.
#extension GL_GOOGLE_include_directive : require
#define AVSM_MARCH_MAP_LOOKUPS
#include "passes/camera/volumes/volume_cached_march.glsl"
