#pragma once
// Deep shadow maps in C++: passes/shadows/techniques/dsm/deep_shadow.glsl compiled with GLM over
// the AVSM core (passes/shadows/techniques/avsm/avsm_core.h), so tests check the deep shadow map build
// (dsm_build.comp runs the same code) on the CPU.
#include <algorithm>
#include <cmath>
#include <span>
#include <vector>

#include "passes/shadows/techniques/avsm/avsm_core.h"
#include "shared/capture.h"

namespace avsm::core {

struct DsmNode {
  float depth, trans;
};

// Internal linkage: the GLSL functions are not inline, and several files include this
// (each uses only some of them).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace {
using shared::CaptureSegment;
using shared::kListEnd;
using shared::uint;

// A subgroup of one lane.
bool subgroupAny(bool value) { return value; }

// What deep_shadow.glsl leaves to its includer: the texel's list nodes, and where its
// compressed nodes go.
struct DsmTexel {
  std::span<const CaptureSegment> list_nodes;
  std::vector<DsmNode> nodes;
};
CaptureSegment dsm_segment(const DsmTexel& texel, uint node) { return texel.list_nodes[node]; }
void dsm_emit(DsmTexel& texel, float depth, float trans) { texel.nodes.push_back({depth, trans}); }
bool dsm_sweep_again(DsmTexel&) { return false; }  // the nodes are kept as they come

#define AVSM_INOUT(T) T&
#include "deep_shadow.glsl"
#undef AVSM_INOUT

// The deep shadow map of the list from `head` in `list_nodes` (linked by `next`), as
// dsm_build.comp builds a texel's.
std::vector<DsmNode> dsm_build_list(std::span<const CaptureSegment> list_nodes, uint head, float far_depth,
                                    float error) {
  DsmTexel texel{list_nodes, {}};
  DsmSweep sweep = dsm_sweep_begin(head, far_depth, error);
  while (!sweep.done) dsm_sweep_steps(sweep, texel, head, far_depth, error, 1 << 30);
  return texel.nodes;
}

// Lokovic & Veach's compression of any curve given as nodes front to back.
std::vector<DsmNode> dsm_compress(std::span<const DsmNode> exact, float error) {
  DsmTexel texel;
  DsmCompressor compressor = dsm_compressor_begin(error);
  for (const DsmNode& node : exact) dsm_compress_node(compressor, node.depth, node.trans, texel);
  dsm_compress_finish(compressor, texel);
  return texel.nodes;
}
}  // namespace
#pragma GCC diagnostic pop

// A curve given by its nodes at depth d: 1 in front of the first, linear between
// nodes (at a step's depth, the value behind it), the last node's value behind the
// last (as dsm_lookup reads a texel, unclamped and linear).
inline float dsm_evaluate(std::span<const DsmNode> nodes, float d) {
  size_t behind = 0;  // nodes at or in front of d
  while (behind < nodes.size() && nodes[behind].depth <= d) ++behind;
  if (behind == 0) return 1.0f;
  if (behind == nodes.size()) return nodes.back().trans;
  const DsmNode &a = nodes[behind - 1], &b = nodes[behind];
  return a.trans + (b.trans - a.trans) * (d - a.depth) / (b.depth - a.depth);  // a.depth <= d < b.depth
}

// The exact curve at one of its node depths, in front of the depth and at it.
struct DsmExactValue {
  float depth, before, after;
};

// The exact curve of the list from `head` at every depth it has a node at (every segment
// end, clamped to the far depth, and the far depth), computed directly, segment by
// segment, without the build's streaming: what tests hold the build against.
inline std::vector<DsmExactValue> dsm_exact_values(std::span<const shared::CaptureSegment> list_nodes, uint32_t head,
                                                   float far_depth) {
  std::vector<shared::CaptureSegment> list;
  for (uint32_t node = head; node != shared::kListEnd; node = list_nodes[node].next) {
    shared::CaptureSegment s = list_nodes[node];
    s.entry = std::min(s.entry, far_depth);
    s.exit_depth = std::min(std::max(s.exit_depth, s.entry), far_depth);
    list.push_back(s);
  }
  std::vector<float> depths{far_depth};
  for (const shared::CaptureSegment& s : list) {
    depths.push_back(s.entry);
    depths.push_back(s.exit_depth);
  }
  std::sort(depths.begin(), depths.end());
  depths.erase(std::unique(depths.begin(), depths.end()), depths.end());
  std::vector<DsmExactValue> values;
  for (float d : depths) {
    DsmExactValue v{d, 1.0f, 1.0f};
    for (const shared::CaptureSegment& s : list) {
      const float value = avsm_segment_transmittance(s.entry, s.exit_depth, s.exit_trans, d);
      v.before *= value;
      v.after *= s.exit_depth <= d ? s.exit_trans : value;
    }
    values.push_back(v);
  }
  return values;
}

// The largest difference between a curve and the exact one at the exact curve's node
// depths, from in front of each and at it (between them both curves are linear).
inline float dsm_max_error_at_exact_nodes(std::span<const DsmNode> nodes, std::span<const DsmExactValue> exact) {
  float worst = 0.0f;
  for (const DsmExactValue& v : exact) {
    worst = std::max(worst, std::abs(dsm_evaluate(nodes, v.depth) - v.after));
    worst = std::max(worst, std::abs(dsm_evaluate(nodes, std::nextafter(v.depth, -3.4e38f)) - v.before));
  }
  return worst;
}

}  // namespace avsm::core
