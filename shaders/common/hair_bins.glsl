// Binning hair strand segments into a light's 8x8-texel tiles (passes/shadows/fixed_build/hair_bins_pass.h;
// the layout is shared/hair_bins.h). Count, scan and fill are three passes so that a
// tile's bin is one contiguous range: the count pass adds every segment to the tiles
// its ribbon's box overlaps, the scan gives each tile its range (or kHairBinOverflow
// when the entries would not fit), and the fill writes the segment indices.
#ifndef AVSM_HAIR_BINS_GLSL
#define AVSM_HAIR_BINS_GLSL
#extension GL_GOOGLE_include_directive : require
#include "shared/hair_bins.h"
#include "shared/passes/shadows/fixed_build/hair_bins.h"
#ifdef AVSM_HAIR_BINS_SEGMENTS
#include "common/hair_footprint.glsl"
#endif

layout(std430, binding = 3) buffer HairTiles { uint hair_tiles[]; };
layout(std430, binding = 4) buffer HairBinEntries { uint hair_bin_entries[]; };
layout(std430, binding = 5) buffer FixedBuildCounter { uint fixed_counters[4]; };

#ifdef AVSM_HAIR_BINS_SEGMENTS
// The tiles segment `s`'s ribbon may cover: (first x, first y, last x, last y), empty
// when last < first.
ivec4 segment_tiles(uint s) {
  HairFootprint f = hair_footprint(s, pc.view_projection, pc.facing_point.xyz, vec4(0.0), float(pc.resolution));
  ivec4 texels = hair_footprint_texels(f, int(pc.resolution));
  if (any(lessThan(texels.zw, texels.xy))) return ivec4(0, 0, -1, -1);
  return texels / int(kHairTileSize);
}
#endif

#endif
