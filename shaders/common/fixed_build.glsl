// A light's map built straight from its casters, without per-fragment lists
// (passes/shadows/fixed_build/fixed_build_pass.h): one workgroup per 8x8 tile of the map, one thread per
// texel, the texel's state (an AVSM curve, opacity planes, Fourier terms) in registers
// from start to end. Each texel takes, in this order:
//   1. the nearest opaque caster (the light depth image) as one blocking segment;
//      anything that starts behind it is rejected before it is taken;
//   2. every hair strand crossing, in segment order: the tile's bin (hair_bins_*.comp)
//      is put in segment order, then walked in batches of 64 ribbons that every
//      thread tests its texel centre against (a tile whose bin did not fit walks
//      every segment instead);
//   3. the smoke along the texel's ray, segment by segment as the march goes.
// The order is fixed, so the result is the same on every run without any sort of
// fragments. Smoke density comes from the brick atlas.
//
// The includer (a technique's <name>_fixed_build.comp) defines, after including:
//   void fixed_clear();                        // the empty texel
//   void fixed_take(float entry_depth, float exit_depth, float transmittance);
//   void fixed_store(uint texel_index);        // into `map_texels`
// and may read `pc` (shared/passes/shadows/fixed_build/fixed_build.h).
#ifndef AVSM_FIXED_BUILD_GLSL
#define AVSM_FIXED_BUILD_GLSL
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require

#define AVSM_VOLUME_BINDING_NANOVDB 0
#define AVSM_VOLUME_BINDING_MAJORANTS 1
#define AVSM_VOLUME_BINDING_PARAMETERS 2
#define AVSM_VOLUME_BINDING_ATLAS 3  // the atlas, and its brick slots at 4
#define AVSM_HAIR_BINDING 5          // points, segments, strands
#include "shared/hair_bins.h"
#include "shared/passes/shadows/fixed_build/fixed_build.h"

// The numbers packed in pc.sizes (fixed_build_sizes()).
uint fixed_technique_size() { return pc.sizes & 0xffu; }
uint fixed_samples_per_segment() { return (pc.sizes >> 8u) & 0xffu; }
uint fixed_volume_count() { return pc.sizes >> 16u; }

layout(local_size_x = 8, local_size_y = 8) in;
layout(binding = 8) uniform sampler2D light_depth;
layout(std430, binding = 9) readonly buffer HairTiles { uint hair_tiles[]; };
layout(std430, binding = 10) buffer HairBinEntries { uint hair_bin_entries[]; };
layout(std430, binding = 11) buffer FixedBuildCounter { uint fixed_counters[4]; };
layout(std430, binding = 12) writeonly buffer Map { vec4 map_texels[]; };

void fixed_clear();
void fixed_take(float entry_depth, float exit_depth, float transmittance);
void fixed_store(uint texel_index);

float blocker_end = 3.4e38;  // the nearest opaque caster's far side: T is 0 behind it
uint inserted = 0u;

void insert(float entry_depth, float exit_depth, float transmittance) {
  if (entry_depth >= blocker_end) return;  // early rejection
  fixed_take(entry_depth, exit_depth, transmittance);
  ++inserted;
}

void smoke_light_segment(ivec2 texel, float entry_depth, float exit_depth, float transmittance) {
  insert(entry_depth, exit_depth, transmittance);
}
#include "common/smoke_light_march.glsl"
#include "common/hair_footprint.glsl"

float texel_thickness(float depth) { return pc.texel_size.x + pc.texel_size.y * depth; }

// ---- 1. opaque ----
void insert_opaque(ivec2 texel, mat4 world_from_light) {
  float z = texelFetch(light_depth, texel, 0).r;
  if (z >= 1.0) return;  // no opaque caster
  vec2 ndc = (vec2(texel) + 0.5) / float(pc.resolution) * 2.0 - 1.0;
  vec4 world = world_from_light * vec4(ndc, z, 1.0);
  float depth = dot(pc.depth_plane.xyz, world.xyz / world.w) + pc.depth_plane.w;
  float exit_depth = depth + texel_thickness(depth);  // the capture's opaque segment
  insert(depth, exit_depth, 0.0);
  blocker_end = exit_depth;
}

// ---- 2. hair ----
shared vec4 ribbon_x[64], ribbon_y[64], ribbon_depth[64], ribbon_inverse_w[64];
shared float ribbon_transmittance[64];  // < 0: no ribbon in this slot

// A texel's crossings of a run of kRibbonRun ribbons (depth, transmittance), in ribbon
// order. Each texel first finds its crossings, then the subgroup inserts them in step:
// a ribbon covers one or two texels of a subgroup, and inserting as each test passes
// would run the insertion (the same instructions in every lane) once per crossing
// instead of once per round of crossings.
const uint kRibbonRun = 16u;
shared vec2 crossings[kRibbonRun][64];

// Puts hair_bin_entries[offset, offset + count) in ascending order: a bitonic network
// over the next power of two whose every comparison puts the smaller value first, so
// the missing entries past `count` act as +infinity and never move.
void order_bin(uint offset, uint count) {
  uint size = 1u;
  while (size < count) size <<= 1u;
  for (uint block = 2u; block <= size; block <<= 1u) {
    for (uint stride = block; stride > 1u; stride >>= 1u) {
      bool flip = stride == block;  // the block's first step compares mirrored pairs
      uint half_stride = stride >> 1u;
      for (uint base = 0u; base < size; base += 64u) {
        uint i = base + gl_LocalInvocationIndex;
        uint partner = flip ? (i ^ (block - 1u)) : (i ^ half_stride);
        if (i < size && partner > i && partner < count) {
          uint a = hair_bin_entries[offset + i], b = hair_bin_entries[offset + partner];
          if (a > b) {
            hair_bin_entries[offset + i] = b;
            hair_bin_entries[offset + partner] = a;
          }
        }
      }
      memoryBarrierBuffer();
      barrier();
    }
  }
}

void insert_hair(ivec2 texel, bool in_map) {
  uint tile = gl_WorkGroupID.y * hair_tiles_per_row(pc.resolution) + gl_WorkGroupID.x;
  uint count = hair_tiles[hair_tile_count_word(tile)];
  uint offset = hair_tiles[hair_tile_offset_word(tile)];
  bool walk_all = offset == kHairBinOverflow;
  uint n = walk_all ? pc.segment_count : count;  // walking all: segments first_segment + i
  if (!walk_all) order_bin(offset, count);
  ivec2 tile_first = ivec2(gl_WorkGroupID.xy) * int(kHairTileSize);
  vec2 centre = vec2(texel) + 0.5;
  for (uint base = 0u; base < n; base += 64u) {
    uint i = base + gl_LocalInvocationIndex;
    float transmittance = -1.0;
    if (i < n) {
      uint s = walk_all ? pc.first_segment + i : hair_bin_entries[offset + i];
      HairFootprint f = hair_footprint(s, pc.light_from_world, pc.facing_point.xyz, pc.depth_plane,
                                       float(pc.resolution));
      ivec4 box = hair_footprint_texels(f, int(pc.resolution));
      ivec2 tile_last = tile_first + int(kHairTileSize) - 1;
      bool overlaps = all(lessThanEqual(box.xy, box.zw)) && all(lessThanEqual(box.xy, tile_last)) &&
                      all(greaterThanEqual(box.zw, tile_first));
      if (overlaps) {
        ribbon_x[gl_LocalInvocationIndex] = f.x;
        ribbon_y[gl_LocalInvocationIndex] = f.y;
        ribbon_depth[gl_LocalInvocationIndex] = f.depth;
        ribbon_inverse_w[gl_LocalInvocationIndex] = f.inverse_w;
        transmittance = 1.0 - f.opacity;
      }
    }
    ribbon_transmittance[gl_LocalInvocationIndex] = transmittance;
    barrier();
    uint batch = min(64u, n - base);
    for (uint run = 0u; run < 64u; run += kRibbonRun) {
      if (run >= batch) break;  // the same bound in every lane
      uint found = 0u;
      for (uint k = run; k < run + kRibbonRun; ++k) {
        if (k >= batch) break;
        float t = ribbon_transmittance[k];
        HairFootprint f;
        f.x = ribbon_x[k];
        f.y = ribbon_y[k];
        f.depth = ribbon_depth[k];
        f.inverse_w = ribbon_inverse_w[k];
        float depth;
        if (in_map && t >= 0.0 && hair_footprint_covers(f, centre, depth) && depth < blocker_end) {
          // The slot by a loop counter, the same in every lane: stored at a per-lane
          // index, lavapipe wrote other workgroup memory (an OSM build's planes) too.
          for (uint slot = 0u; slot < kRibbonRun; ++slot)
            if (slot == found) crossings[slot][gl_LocalInvocationIndex] = vec2(depth, t);
          ++found;
        }
      }
      for (uint j = 0u; j < kRibbonRun; ++j) {
        if (!subgroupAny(j < found)) break;  // the subgroup's longest run of crossings
        if (j < found) {
          vec2 c = crossings[j][gl_LocalInvocationIndex];
          insert(c.x, c.x + texel_thickness(c.x), c.y);
        }
      }
    }
    barrier();
  }
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  // No early return: the hair batches synchronise the workgroup.
  bool in_map = all(lessThan(uvec2(texel), uvec2(pc.resolution)));
  mat4 world_from_light = inverse(pc.light_from_world);
  fixed_clear();
  if (in_map) insert_opaque(texel, world_from_light);
  if (pc.segment_count > 0u) insert_hair(texel, in_map);
  if (!in_map) return;
  march_smoke_from_light(texel, uvec2(0u), pc.resolution, world_from_light, pc.depth_plane, fixed_volume_count(),
                         pc.volume_mask, fixed_samples_per_segment(), blocker_end);
  fixed_store(uint(texel.y) * pc.resolution + uint(texel.x));
  if (inserted > 0u) atomicAdd(fixed_counters[kFixedCounterInserted], inserted);
}

#endif
