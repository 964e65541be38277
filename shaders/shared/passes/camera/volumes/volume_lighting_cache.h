// Push constants of the volume lighting cache (volume_lighting_cache.comp).
#ifndef AVSM_SHARED_PASSES_VOLUME_LIGHTING_CACHE_H
#define AVSM_SHARED_PASSES_VOLUME_LIGHTING_CACHE_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

#define GPU_VOLUME_LIGHTING_CACHE_PUSH(F, A)\
  F(vec3, camera_position)  \
  F(uint, volume_count)     \
  F(uvec3, image_size)      \
  F(uint, light_count)
GPU_PUSH_CONSTANTS(VolumeLightingCachePush, GPU_VOLUME_LIGHTING_CACHE_PUSH)

GPU_NAMESPACE_END
#endif
