// Hair strand segments binned into light-space tiles for the fixed-memory AVSM build
// (passes/shadows/fixed_build/hair_bins_pass.h, passes/shadows/techniques/avsm/avsm_fixed_build.comp). Per tile three
// words: how many segments overlap it, where its bin starts in the entry buffer
// (kHairBinOverflow: it did not fit, the build walks every segment for that tile) and
// a fill cursor. Entries are segment indices.
#ifndef AVSM_SHARED_HAIR_BINS_H
#define AVSM_SHARED_HAIR_BINS_H
#include "shared/gpu_struct.h"
GPU_NAMESPACE_BEGIN

GPU_CONST(uint, kHairTileSize, 8u)  // texels per side; the build's workgroup is one tile
// Entry capacity per strand segment: a segment overlaps one to four 8x8 tiles unless it
// spans more than a tile on the light's map.
GPU_CONST(uint, kHairBinEntriesPerSegment, 4u)
GPU_CONST(uint, kHairBinOverflow, 0xffffffffu)
GPU_CONST(uint, kHairTileWords, 3u)

GPU_FUNCTION uint hair_tiles_per_row(uint resolution) { return (resolution + kHairTileSize - 1u) / kHairTileSize; }

GPU_FUNCTION uint hair_tile_count_word(uint tile) { return kHairTileWords * tile; }
GPU_FUNCTION uint hair_tile_offset_word(uint tile) { return kHairTileWords * tile + 1u; }
GPU_FUNCTION uint hair_tile_cursor_word(uint tile) { return kHairTileWords * tile + 2u; }

// The light's capture counter words in the fixed build (passes/shadows/capture/capture_lists.h has the lists').
GPU_CONST(uint, kFixedCounterInserted, 0u)     // segments inserted into curves
GPU_CONST(uint, kFixedCounterBinEntries, 2u)   // bin entries asked for
GPU_CONST(uint, kFixedCounterTilesWalked, 3u)  // tiles whose bin did not fit

GPU_NAMESPACE_END
#endif
