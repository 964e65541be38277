#version 460
// Hair binning, 2 of 3: each tile's bin offset, an exclusive prefix sum of the counts in
// tile order (one workgroup: per thread a run of tiles, then a scan of the runs).
// A bin that would end past the entry capacity gets kHairBinOverflow: the fill skips
// it and the build walks every segment for that tile instead (never dropping one).
#extension GL_GOOGLE_include_directive : require
#include "common/hair_bins.glsl"

layout(local_size_x = 256) in;
shared uint run_sums[256];

void main() {
  uint tile_count = pc.tiles_per_row * pc.tiles_per_row;
  uint per_thread = (tile_count + 255u) / 256u;
  uint first = gl_LocalInvocationIndex * per_thread;
  uint sum = 0u;
  for (uint k = 0u; k < per_thread; ++k)
    if (first + k < tile_count) sum += hair_tiles[hair_tile_count_word(first + k)];
  run_sums[gl_LocalInvocationIndex] = sum;
  barrier();
  // Inclusive scan of the runs (Hillis-Steele).
  for (uint d = 1u; d < 256u; d <<= 1u) {
    uint add = gl_LocalInvocationIndex >= d ? run_sums[gl_LocalInvocationIndex - d] : 0u;
    barrier();
    run_sums[gl_LocalInvocationIndex] += add;
    barrier();
  }
  uint offset = run_sums[gl_LocalInvocationIndex] - sum;
  uint walked = 0u;
  for (uint k = 0u; k < per_thread; ++k) {
    uint t = first + k;
    if (t >= tile_count) continue;
    uint count = hair_tiles[hair_tile_count_word(t)];
    bool fits = offset + count <= pc.entry_capacity;
    hair_tiles[hair_tile_offset_word(t)] = fits ? offset : kHairBinOverflow;
    if (!fits) ++walked;
    offset += count;
  }
  if (walked > 0u) atomicAdd(fixed_counters[kFixedCounterTilesWalked], walked);
}
