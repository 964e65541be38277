#version 460
// The fast upsample and finish (shaders/passes/camera/volumes/volume_upsample.glsl), for volumes that all have a lighting cache.
#extension GL_GOOGLE_include_directive : require
#include "passes/camera/volumes/volume_upsample.glsl"
