#version 460
// The fast upsample and finish (shaders/passes/volume_upsample.glsl), for volumes that all have a lighting cache.
#extension GL_GOOGLE_include_directive : require
#include "passes/volume_upsample.glsl"
