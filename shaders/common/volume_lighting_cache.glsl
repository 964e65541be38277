// The volume lighting cache (passes/camera/volumes/volume_lighting_cache_pass.h): per fog volume a
// box of cells over its support, each holding the radiance scattered towards the
// camera per unit sigma_s at its centre (sum over lights of radiance * phase * the
// light's map transmittance). All volumes' boxes are stacked along z in one 3D image.
// (GpuCacheLayout: shared/volume.h.)
//
// Before including, define AVSM_CACHE_BINDING: the cache layouts (one per volume) at
// that binding; with AVSM_CACHE_SAMPLED also the cache image (sampler3D) at +1.
#ifndef AVSM_VOLUME_LIGHTING_CACHE_GLSL
#define AVSM_VOLUME_LIGHTING_CACHE_GLSL

#extension GL_GOOGLE_include_directive : require
#include "shared/volume.h"

layout(std430, binding = AVSM_CACHE_BINDING) readonly buffer CacheLayouts { GpuCacheLayout cache_layouts[]; };

#ifdef AVSM_CACHE_SAMPLED
layout(binding = AVSM_CACHE_BINDING + 1) uniform sampler3D lighting_cache;

// The cache trilinearly at an index-space position of volume v. Coordinates are
// clamped half a cell inside the volume's box so that no other volume's cells bleed in.
vec3 cached_in_scattering(GpuCacheLayout layout_v, vec3 index_position) {
  vec3 cell = (index_position - layout_v.cell_origin) * layout_v.cells_per_voxel;
  cell = clamp(cell, vec3(0.5), vec3(layout_v.dims) - 0.5) + vec3(0.0, 0.0, float(layout_v.first_slice));
  return textureLod(lighting_cache, cell / vec3(textureSize(lighting_cache, 0)), 0.0).rgb;
}
#endif

#endif
