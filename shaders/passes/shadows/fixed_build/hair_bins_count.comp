#version 460
// Hair binning, 1 of 3: per strand segment, count it in every tile its ribbon may cover
// (common/hair_bins.glsl).
#extension GL_GOOGLE_include_directive : require
#define AVSM_HAIR_BINS_SEGMENTS
#include "common/hair_bins.glsl"

layout(local_size_x = 64) in;

void main() {
  if (gl_GlobalInvocationID.x >= pc.segment_count) return;
  uint s = pc.first_segment + gl_GlobalInvocationID.x;
  ivec4 tiles = segment_tiles(s);
  uint entries = 0u;
  for (int y = tiles.y; y <= tiles.w; ++y)
    for (int x = tiles.x; x <= tiles.z; ++x) {
      atomicAdd(hair_tiles[hair_tile_count_word(uint(y) * pc.tiles_per_row + uint(x))], 1u);
      ++entries;
    }
  if (entries > 0u) atomicAdd(fixed_counters[kFixedCounterBinEntries], entries);
}
