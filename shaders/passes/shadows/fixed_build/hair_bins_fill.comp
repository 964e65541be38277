#version 460
// Hair binning, 3 of 3: write every segment's index into the bins the count pass
// counted it in. Slots come from atomics, so a bin's order varies from run to run;
// the build puts each bin in segment order before it uses it.
#extension GL_GOOGLE_include_directive : require
#define AVSM_HAIR_BINS_SEGMENTS
#include "common/hair_bins.glsl"

layout(local_size_x = 64) in;

void main() {
  if (gl_GlobalInvocationID.x >= pc.segment_count) return;
  uint s = pc.first_segment + gl_GlobalInvocationID.x;
  ivec4 tiles = segment_tiles(s);
  for (int y = tiles.y; y <= tiles.w; ++y)
    for (int x = tiles.x; x <= tiles.z; ++x) {
      uint tile = uint(y) * pc.tiles_per_row + uint(x);
      uint offset = hair_tiles[hair_tile_offset_word(tile)];
      if (offset == kHairBinOverflow) continue;
      uint slot = atomicAdd(hair_tiles[hair_tile_cursor_word(tile)], 1u);
      hair_bin_entries[offset + slot] = s;
    }
}
