// Area lights' soft shadows from subsets of their K virtual lights (seed 003 gathers its
// virtual lights interleaved the same way), so that a receiver's cost does not grow with K:
// - opaque surfaces look up kAreaShadowLookups virtual lights per pixel, the subset their
//   place in a tile of pixels picks, and the area-shadow filter averages a tile of pixels
//   around each, which between them look up every virtual light
//   (passes/camera/surfaces/area_shadow_filter_pass.h);
// - hair vertices, fog froxels and smoke cache cells look up kMediaAreaLookups each, a
//   subset spread over the whole light, the subset their index picks; the ribbons, the
//   fog's integration and the cache's interpolation average neighbouring subsets.
// A subset of `size` holds the virtual lights shadow_lookup.glsl's
// area_light_subset_member() lists.
#ifndef AVSM_SHARED_AREA_SHADOWS_H
#define AVSM_SHARED_AREA_SHADOWS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

GPU_CONST(uint, kAreaShadowLookups, 2u)
GPU_CONST(uint, kMediaAreaLookups, 16u)
// The widest tile (K = 256: 128 subsets, 12 x 12 pixels).
GPU_CONST(uint, kAreaShadowMaxTile, 12u)

// Subsets of `size` virtual lights (the last may hold fewer).
GPU_FUNCTION uint area_light_subsets(uint virtual_lights, uint size) { return (virtual_lights + size - 1u) / size; }

// Whether a light's surface lookups take subsets: an area light with more virtual lights
// than one pixel looks up.
GPU_FUNCTION bool area_shadow_takes_subsets(uint virtual_lights) { return virtual_lights > kAreaShadowLookups; }

// Pixels per side of the tile whose pixels look up every subset: the smallest square
// with room for them all.
GPU_FUNCTION uint area_shadow_tile(uint virtual_lights) {
  uint subsets = area_light_subsets(virtual_lights, kAreaShadowLookups);
  for (uint side = 1u; side < kAreaShadowMaxTile; ++side)  // a constant bound (lavapipe)
    if (side * side >= subsets) return side;
  return kAreaShadowMaxTile;
}

// The subset a pixel looks up, from its place in the tile (row by row; places beyond the
// last subset take the first ones again).
GPU_FUNCTION uint area_shadow_subset(uint x, uint y, uint virtual_lights) {
  uint side = area_shadow_tile(virtual_lights);
  return ((x % side) + side * (y % side)) % area_light_subsets(virtual_lights, kAreaShadowLookups);
}

GPU_NAMESPACE_END
#endif
