// Area lights' soft shadows on opaque surfaces, filtered in screen space
// (passes/camera/surfaces/area_shadow_filter_pass.h; seed 003's interleaved gather): each
// pixel looks its light up in kAreaShadowLookups of the K virtual lights' maps, the subset
// its place in a tile of pixels picks, and the filter averages a tile of pixels around
// each, which between them look up every virtual light. The cost per pixel stays that of
// kAreaShadowLookups maps whatever K.
#ifndef AVSM_SHARED_AREA_SHADOWS_H
#define AVSM_SHARED_AREA_SHADOWS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

GPU_CONST(uint, kAreaShadowLookups, 4u)
// The widest tile (K = 256: 64 subsets, 8 x 8 pixels).
GPU_CONST(uint, kAreaShadowMaxTile, 8u)

// Subsets of kAreaShadowLookups virtual lights (the last may hold fewer).
GPU_FUNCTION uint area_shadow_subsets(uint virtual_lights) {
  return (virtual_lights + kAreaShadowLookups - 1u) / kAreaShadowLookups;
}

// Whether a light's surface lookups take subsets: an area light with more virtual lights
// than one pixel looks up.
GPU_FUNCTION bool area_shadow_takes_subsets(uint virtual_lights) { return virtual_lights > kAreaShadowLookups; }

// Pixels per side of the tile whose pixels look up every subset: the smallest square
// with room for them all.
GPU_FUNCTION uint area_shadow_tile(uint virtual_lights) {
  uint subsets = area_shadow_subsets(virtual_lights);
  for (uint side = 1u; side < kAreaShadowMaxTile; ++side)  // a constant bound (lavapipe)
    if (side * side >= subsets) return side;
  return kAreaShadowMaxTile;
}

// The first virtual light a pixel looks up: its subset's, from its place in the tile
// (row by row; places beyond the last subset take the first ones again).
GPU_FUNCTION uint area_shadow_first_view(uint x, uint y, uint virtual_lights) {
  uint side = area_shadow_tile(virtual_lights);
  uint place = (x % side) + side * (y % side);
  return (place % area_shadow_subsets(virtual_lights)) * kAreaShadowLookups;
}

GPU_NAMESPACE_END
#endif
