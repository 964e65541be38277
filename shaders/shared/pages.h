// Paged transmittance maps (shadow.layout "paged"; seed 002, GPU adaptive shadow maps):
// a light map is a virtual square of `virtual_resolution` texels with mip levels, cut
// into pages of `page_size` texels per side. Only the pages the camera's receivers ask
// for are built, each into a slot of a fixed pool, and kept from frame to frame.
//
// A paged map's region of the shadow atlas (GpuShadow::map_offset) starts with its page
// table: one word per page of every level, level 0 (the finest) first, pages row by
// row; 0 is a page without a slot, else its slot + 1. The pool follows at
// GpuShadow::page_pool_offset: slot after slot, each an ordinary dense AVSM map of
// page_size texels, one level (shared/map_layouts.h). The coarsest level is one page
// that is always resident, so every lookup finds a level.
//
// Receivers mark the pages they read in a request bit field per map
// (GpuShadow::page_requests_offset, in words of the request buffer): bit i of word
// i / 32 is page-table entry i.
#ifndef AVSM_SHARED_PAGES_H
#define AVSM_SHARED_PAGES_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

// GpuShadow::page_size of a dense map.
GPU_CONST(uint, kDenseLayout, 0u)
// GpuShadow::page_requests_offset when nothing marks the map's pages.
GPU_CONST(uint, kNoPageRequests, 0xffffffffu)
// A page-table word: no slot.
GPU_CONST(uint, kPageAbsent, 0u)

// Levels of a virtual map: from virtual_resolution texels down to one page.
GPU_FUNCTION uint page_level_count(uint virtual_resolution, uint page_size) {
  uint levels = 1u;
  while ((virtual_resolution >> levels) >= page_size) levels += 1u;
  return levels;
}

// Pages per side at `level`.
GPU_FUNCTION uint page_grid(uint virtual_resolution, uint page_size, uint level) {
  return max((virtual_resolution >> level) / page_size, 1u);
}

// Page-table entry of the first page of `level`: the pages of the levels before it, a
// geometric series (G^2 + (G/2)^2 + ... = 4/3 (G^2 - g^2), with G the level-0 grid and g
// this level's), in closed form so that shaders need no loop with a per-lane bound.
GPU_FUNCTION uint page_table_level_first(uint virtual_resolution, uint page_size, uint level) {
  uint grid0 = virtual_resolution / page_size, grid = grid0 >> level;
  return 4u * (grid0 * grid0 - grid * grid) / 3u;
}

GPU_FUNCTION uint page_table_entries(uint virtual_resolution, uint page_size) {
  uint grid0 = virtual_resolution / page_size;
  return (4u * grid0 * grid0 - 1u) / 3u;  // every level down to one page
}

// The most levels a virtual map has (16384 texels in pages of 32).
GPU_CONST(uint, kMaxPageLevels, 10u)

// vec4s of a slot: page_size^2 texels of nodes / 4 vec4s each.
GPU_FUNCTION uint page_slot_vec4s(uint page_size, uint nodes) { return page_size * page_size * (nodes / 4u); }

GPU_NAMESPACE_END
#endif
