#version 460
// The fast camera march (shaders/passes/camera/volumes/volume_cached_march.glsl), for volumes that all have a lighting cache.
#extension GL_GOOGLE_include_directive : require
#include "passes/camera/volumes/volume_cached_march.glsl"
