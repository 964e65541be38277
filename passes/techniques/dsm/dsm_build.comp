#version 460
// Deep shadow map build (technique dsm): per light texel, the exact transmittance
// curve of its capture list (the AVSM core's streaming insertion with room for 16
// nodes: exact up to 7 overlapping segments, trimmed by the smallest-area rule
// beyond; curves of 32 or 64 nodes came out corrupt on lavapipe), compressed by
// Lokovic & Veach's greedy rule to the user error, and stored with a variable node count: a per-texel header (first node, count) and
// a node pool shared by the texels, allocated with an atomic counter.
// The map's words: shared/map_layouts.h.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#define AVSM_CURVE_CAPACITY 18
#define AVSM_CAPTURE_BINDING 0
#include "common/capture_lists.glsl"
#include "avsm/avsm_core.glsl"
#include "techniques/deep_shadow.glsl"
#include "shared/map_layouts.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 2) buffer Map { uint words[]; };
// The light's host-readable capture counter: word 1 gathers the pool nodes asked for.
layout(std430, binding = 3) buffer Counter { uint counter_words[]; };

#include "shared/passes/map_build.h"

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.resolution)))) return;
  AvsmCurve curve = avsm_clear(pc.far_depth);
  for (uint node = imageLoad(capture_heads, texel).r; node != kListEnd; node = capture_nodes[node].next) {
    CaptureSegment s = capture_nodes[node];
    avsm_insert_segment(curve, s.entry, s.exit_depth, s.exit_trans, int(pc.count));
  }

  AvsmCurve compressed;
  dsm_compress(curve, pc.error, compressed);

  uint index = uint(texel.y) * pc.resolution + uint(texel.x);
  uint count = uint(compressed.count);
  uint first = atomicAdd(words[0], count);
  atomicAdd(counter_words[1], count);
  uint pool = dsm_pool_base(pc.resolution);
  uint capacity = (uint(words.length()) - pool) / 2u;
  bool fits = first + count <= capacity;
  words[dsm_first_node_word(index)] = first;
  words[dsm_node_count_word(index)] = fits ? count : kDsmLost;
  if (!fits) return;
  for (uint k = 0u; k < uint(AVSM_CURVE_CAPACITY); ++k) {  // constant bound: see avsm_core.glsl
    if (k >= count) break;
    words[pool + 2u * (first + k)] = floatBitsToUint(compressed.depth[k]);
    words[pool + 2u * (first + k) + 1u] = floatBitsToUint(compressed.trans[k]);
  }
}
