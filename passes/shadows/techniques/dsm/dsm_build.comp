#version 460
// Deep shadow map build (technique dsm): per light texel, the exact transmittance
// curve of its whole capture list streamed into Lokovic & Veach's greedy compression
// to the user error (passes/shadows/techniques/dsm/deep_shadow.glsl), stored with a variable
// node count: a per-texel header (first node, count) and a node pool shared by the
// texels. The count is known only once the curve is compressed, so each texel sweeps
// its curve twice: counting the nodes, then (after taking that many from the pool with
// an atomic counter) writing them. The map's words: shared/map_layouts.h.
//
// lavapipe ends a shader's loops after 65535 passes in all, and a sweep takes O(n^2)
// passes for n segments, so the build is several dispatches of this shader (push
// constant `count`: which one). Dispatch 0 counts each list, asks for the dispatches
// it needs (counter word 2; the next frame has that many) and starts the texel's
// build; every later one goes on with it for up to kPassesPerDispatch loop passes,
// keeping it between dispatches in the map's builds (bound on their own as Builds). A texel whose build did not finish reads
// as unshadowed (its count stays kDsmLost) and is reported.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#define AVSM_CAPTURE_BINDING 0
#include "common/capture_lists.glsl"
#include "avsm/avsm_core.glsl"
#include "shared/map_layouts.h"

layout(local_size_x = 8, local_size_y = 8) in;
layout(std430, binding = 2) buffer Map { uint words[]; };
// The light's host-readable capture counter: word 1 gathers the pool nodes asked for,
// word 2 the most dispatches a texel needs.
layout(std430, binding = 3) buffer Counter { uint counter_words[]; };

#include "shared/passes/shadows/techniques/map_build.h"

// Loop passes per dispatch: lavapipe's 65535, less room for the few other loops.
const int kPassesPerDispatch = 60000;

// A texel's compressed nodes: counted in a first sweep of its curve, then written to
// the pool from node `first` in a second one, when they fit.
struct DsmTexel {
  uint index;  // row by row
  uint first;
  uint count;
  bool write;
};

CaptureSegment dsm_segment(DsmTexel texel, uint node) { return capture_nodes[node]; }

void dsm_emit(inout DsmTexel texel, float depth, float trans) {
  if (texel.write) {
    uint word = dsm_pool_base(pc.resolution) + 2u * (texel.first + texel.count);
    words[word] = floatBitsToUint(depth);
    words[word + 1u] = floatBitsToUint(trans);
  }
  texel.count += 1u;
}

// After the counting sweep: takes room in the pool; the nodes follow in a second sweep
// if they fit. Nodes that do not fit are counted (the pool grows for the next frame).
bool dsm_sweep_again(inout DsmTexel texel) {
  if (texel.write) return false;
  uint count = texel.count;
  uint first = atomicAdd(words[0], count);
  atomicAdd(counter_words[1], count);
  uint capacity = (uint(words.length()) - dsm_pool_base(pc.resolution)) / 2u;
  bool fits = first + count <= capacity;
  words[dsm_first_node_word(texel.index)] = first;
  texel = DsmTexel(texel.index, first, 0u, fits);
  return fits;
}

#include "techniques/dsm/deep_shadow.glsl"

// A texel's build between dispatches: kDsmBuildWords words in the map (shared/map_layouts.h).
struct DsmBuild {
  DsmSweep sweep;
  DsmTexel texel;
};
layout(std430, binding = 4) buffer Builds { DsmBuild builds[]; };

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.resolution)))) return;
  uint index = uint(texel.y) * pc.resolution + uint(texel.x);
  uint head = imageLoad(capture_heads, texel).r;
  if (pc.count == 0u) {
    uint segments = 0u;
    uint node = head;
    while (subgroupAny(node != kListEnd)) {  // in step, as every list walk
      if (node != kListEnd) {
        node = capture_nodes[node].next;
        segments += 1u;
      }
    }
    uint passes = dsm_sweep_passes(segments, 2u);
    atomicMax(counter_words[2], (passes + uint(kPassesPerDispatch) - 1u) / uint(kPassesPerDispatch));
    words[dsm_first_node_word(index)] = 0u;
    words[dsm_node_count_word(index)] = kDsmLost;  // until its nodes are all written
    builds[index] = DsmBuild(dsm_sweep_begin(head, pc.far_depth, pc.error), DsmTexel(index, 0u, 0u, false));
    return;
  }
  DsmBuild build = builds[index];
  if (build.sweep.done) return;
  dsm_sweep_steps(build.sweep, build.texel, head, pc.far_depth, pc.error, kPassesPerDispatch);
  builds[index] = build;
  if (build.sweep.done && build.texel.write) words[dsm_node_count_word(index)] = build.texel.count;
}
