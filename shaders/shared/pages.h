// Paged transmittance maps (shadow.layout "paged"; seed 002, GPU adaptive shadow maps):
// a light map is a virtual square of `virtual_resolution` texels with mip levels, cut
// into pages of `page_size` texels per side. Only the pages the camera's receivers ask
// for are built, each into a slot of a fixed pool, and kept from frame to frame.
//
// A paged map's region of the shadow atlas (GpuShadow::map_offset) starts with its page
// table: one word per page of every level (of a clipmap level's window, below), level 0
// (the finest) first, pages row by row; 0 is a page without a slot, else its slot + 1. The pool follows at
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
// How wide a paged map's texels may be on screen, in camera pixels at their widest: a
// receiver asks for the coarsest level whose texels are no wider (the resolution
// target of issue 33, which capture/resolution.h measures against).
GPU_CONST(float, kPagedTexelPixels, 1.5f)

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

// Clipmap windows (directional lights, whose map covers the scene while the camera sees
// a small part of it): a level wider than `window` pages keeps only a window of
// window^2 pages in the table, centred on the camera's page at that level (each level's
// window covers twice the extent of the finer one's); coarser levels are kept whole.
// A page outside its level's window has no entry: lookups there read a coarser level.
// The window is addressed toroidally (entry = page mod window), so a page that stays in
// the window while the camera moves keeps its entry. window 0: every level whole.

// Levels kept as windows: those wider than `window` pages (both powers of two).
GPU_FUNCTION uint page_window_levels(uint virtual_resolution, uint page_size, uint window) {
  uint levels = 0u;
  if (window == 0u) return 0u;
  for (uint l = 0u; l < 32u; ++l) {  // a constant bound: lavapipe miscompiles per-lane ones
    if ((virtual_resolution / page_size >> l) <= window) break;
    levels += 1u;
  }
  return levels;
}

// Pages per side the table keeps of `level`.
GPU_FUNCTION uint page_table_grid(uint virtual_resolution, uint page_size, uint window, uint level) {
  uint grid = page_grid(virtual_resolution, page_size, level);
  return window == 0u ? grid : min(grid, window);
}

// Page-table entry of the first page of `level`: window^2 per windowed level, then the
// whole levels, a geometric series (G^2 + (G/2)^2 + ... = 4/3 (G^2 - g^2), with G the
// first whole level's grid and g this level's), in closed form so that shaders need no
// loop with a per-lane bound.
GPU_FUNCTION uint page_table_level_first(uint virtual_resolution, uint page_size, uint window, uint level) {
  uint windowed = page_window_levels(virtual_resolution, page_size, window);
  uint grid0 = (virtual_resolution / page_size) >> windowed, grid = grid0 >> (max(level, windowed) - windowed);
  return min(level, windowed) * window * window + 4u * (grid0 * grid0 - grid * grid) / 3u;
}

GPU_FUNCTION uint page_table_entries(uint virtual_resolution, uint page_size, uint window) {
  uint windowed = page_window_levels(virtual_resolution, page_size, window);
  uint grid0 = (virtual_resolution / page_size) >> windowed;
  return windowed * window * window + (4u * grid0 * grid0 - 1u) / 3u;  // every level down to one page
}

// The first page of `level`'s window: `window` pages around the page that holds level-0
// texel `centre` (the camera's), kept inside the level. 0 for a whole level.
GPU_FUNCTION uvec2 page_window_origin(uint virtual_resolution, uint page_size, uint window, uint level, uvec2 centre) {
  uint grid = page_grid(virtual_resolution, page_size, level);
  if (window == 0u || grid <= window) return uvec2(0u, 0u);
  ivec2 page = ivec2((centre >> level) / page_size);
  return uvec2(clamp(page - ivec2(int(window / 2u)), ivec2(0), ivec2(int(grid - window))));
}

// A page-table entry that does not exist: the page lies outside its level's window.
GPU_CONST(uint, kNoPageEntry, 0xffffffffu)

// Entry of page `page` of `level` (within one face's table), or kNoPageEntry.
GPU_FUNCTION uint page_table_entry(uint virtual_resolution, uint page_size, uint window, uint level, uvec2 page,
                                   uvec2 centre) {
  uint grid = page_table_grid(virtual_resolution, page_size, window, level);
  uvec2 origin = page_window_origin(virtual_resolution, page_size, window, level, centre);
  if (page.x < origin.x || page.y < origin.y || page.x >= origin.x + grid || page.y >= origin.y + grid)
    return kNoPageEntry;
  return page_table_level_first(virtual_resolution, page_size, window, level) + (page.y % grid) * grid + page.x % grid;
}

// The most levels a virtual map has (262144 texels in pages of 32).
GPU_CONST(uint, kMaxPageLevels, 14u)

// vec4s of a slot: page_size^2 texels of nodes / 4 vec4s each.
GPU_FUNCTION uint page_slot_vec4s(uint page_size, uint nodes) { return page_size * page_size * (nodes / 4u); }

GPU_NAMESPACE_END
#endif
