// Deep shadow maps (Lokovic & Veach 2000): a texel's exact transmittance curve,
// compressed to as few nodes as keep it within a user error everywhere, with a
// variable node count per texel. Written for GLSL and C++ like the AVSM core
// (include avsm/avsm_core.glsl first; C++ through passes/shadows/techniques/dsm/deep_shadow.h).
//
// The exact curve of a list of any length is never held anywhere (a hair texel has
// thousands of segments): its nodes are streamed front to back straight into the
// compressor, which only ever needs the next one. The exact curve is the product of the list's
// segments (avsm_segment_transmittance), with a node at every segment's entry and
// exit (clamped to the far depth, as the AVSM core clamps them) and one at the far
// depth, linear between nodes. Each node takes one walk of the list (the product at
// its depth, and the next node's depth), so a list of n segments costs O(n^2) time
// and no memory. lavapipe ends a shader's loops after 65535 passes in all (gallivm's
// LP_MAX_TGSI_LOOP_ITERATIONS, shared by every loop of a shader): the sweep stops
// after a given number of passes and goes on from its saved state in a later dispatch.
//
// The includer provides the texel being built:
//   struct DsmTexel: its list's nodes and what takes the compressed nodes;
//   CaptureSegment dsm_segment(DsmTexel texel, uint node): list node `node`
//     (shared/capture.h; its `next` leads on, kListEnd ends the list);
//   void dsm_emit(inout DsmTexel texel, float depth, float trans): the next
//     compressed node, front to back;
//   bool dsm_sweep_again(inout DsmTexel texel): called after each sweep of the
//     curve; true runs it once more (the GPU build counts the nodes, takes room for
//     them and writes them in a second sweep);
// and in C++ subgroupAny (one lane).
#ifndef AVSM_DEEP_SHADOW_GLSL
#define AVSM_DEEP_SHADOW_GLSL

// ---- The exact curve, one node at a time ----

// The exact curve at one depth, gathered over one walk of the list: its value just
// in front of the depth and at it (they differ where a zero-length segment, an opaque
// surface, steps down there), and the depth of the next node behind it.
struct DsmExactNode {
  float depth;
  float before;
  float after;
  float next_depth;  // 3.4e38: none (this is the far node)
};

DsmExactNode dsm_exact_node_begin(float depth, float far_depth) {
  DsmExactNode n;
  n.depth = depth;
  n.before = 1.0f;
  n.after = 1.0f;
  n.next_depth = depth < far_depth ? far_depth : 3.4e38f;  // every curve ends at the far depth
  return n;
}

void dsm_exact_node_add(AVSM_INOUT(DsmExactNode) n, CaptureSegment s, float far_depth) {
  float entry = min(s.entry, far_depth);
  float exit_depth = min(max(s.exit_depth, entry), far_depth);
  float value = avsm_segment_transmittance(entry, exit_depth, s.exit_trans, n.depth);
  n.before *= value;
  n.after *= exit_depth <= n.depth ? s.exit_trans : value;  // a segment ending here counts whole
  if (entry > n.depth) n.next_depth = min(n.next_depth, entry);
  if (exit_depth > n.depth) n.next_depth = min(n.next_depth, exit_depth);
}

// ---- Lokovic & Veach's compression, streamed ----

// From the last emitted node (the origin), follow the exact curve's nodes while one
// line from the origin stays within the error of every one of them (a narrowing
// range of slopes); when no slope fits the next node, emit the line's end at the
// previous node and start again from there. A jump at one depth (an opaque surface)
// that exceeds the error becomes two nodes at that depth. The compressed curve is
// within the error of the exact one at each of its nodes, so everywhere: its nodes
// sit at exact-curve node depths, so both are linear between those. It never has
// more nodes than the exact curve.
struct DsmCompressor {
  float error;
  bool started;          // the first node is emitted as it is
  float origin_depth;    // the last node emitted
  float origin_trans;
  float previous_depth;  // the last exact node taken
  float low;             // slopes from the origin that keep every exact node since within the error
  float high;
};

DsmCompressor dsm_compressor_begin(float error) {
  DsmCompressor c;
  c.error = error;
  c.started = false;
  c.origin_depth = 0.0f;
  c.origin_trans = 1.0f;
  c.previous_depth = 0.0f;
  c.low = -3.4e38f;
  c.high = 3.4e38f;
  return c;
}

// The slope for a line from (origin_depth, origin_trans) to end_depth: one that keeps
// every node so far within the error ([low, high]), preferring one that also ends
// inside [0, 1]. The end value is never clamped afterwards: that would bend the
// line away from the nodes it was fitted to.
float dsm_line_slope(float low, float high, float origin_depth, float origin_trans, float end_depth) {
  if (low <= -3.4e38f) return 0.0f;  // no node constrains it yet (the line ends where it starts)
  float dz = end_depth - origin_depth;
  float in_range_low = max(low, -origin_trans / dz), in_range_high = min(high, (1.0f - origin_trans) / dz);
  return in_range_low <= in_range_high ? 0.5f * (in_range_low + in_range_high) : 0.5f * (low + high);
}

// Ends the line at end_depth: its end is emitted and becomes the origin.
void dsm_end_line(AVSM_INOUT(DsmCompressor) c, float end_depth, AVSM_INOUT(DsmTexel) texel) {
  c.origin_trans += dsm_line_slope(c.low, c.high, c.origin_depth, c.origin_trans, end_depth) * (end_depth - c.origin_depth);
  c.origin_depth = end_depth;
  dsm_emit(texel, c.origin_depth, c.origin_trans);
  c.low = -3.4e38f;
  c.high = 3.4e38f;
}

// Takes the node into the line from the origin if it fits (or is a step at the origin's
// depth, emitted when it exceeds the error); false when no slope fits it.
bool dsm_fit_node(AVSM_INOUT(DsmCompressor) c, float depth, float trans, AVSM_INOUT(DsmTexel) texel) {
  float dz = depth - c.origin_depth;
  if (dz <= 1e-7f) {  // same depth as the origin: a step
    if (abs(trans - c.origin_trans) > c.error) {
      c.origin_trans = trans;
      dsm_emit(texel, c.origin_depth, c.origin_trans);
      c.low = -3.4e38f;
      c.high = 3.4e38f;
    }
    return true;
  }
  float new_low = max(c.low, (trans - c.error - c.origin_trans) / dz);
  float new_high = min(c.high, (trans + c.error - c.origin_trans) / dz);
  if (new_low > new_high) return false;
  c.low = new_low;
  c.high = new_high;
  return true;
}

// Takes the exact curve's next node (depths never decrease).
void dsm_compress_node(AVSM_INOUT(DsmCompressor) c, float depth, float trans, AVSM_INOUT(DsmTexel) texel) {
  if (!c.started) {
    c.started = true;
    c.origin_depth = depth;
    c.origin_trans = trans;
    c.previous_depth = depth;
    dsm_emit(texel, depth, trans);
    return;
  }
  // A node that does not fit ends the line at the previous node and is taken again
  // from there, where any slope is still open: then it fits, or is a step.
  if (!dsm_fit_node(c, depth, trans, texel)) {
    dsm_end_line(c, c.previous_depth, texel);
    dsm_fit_node(c, depth, trans, texel);
  }
  c.previous_depth = depth;
}

// After the last exact node: the last line ends there.
void dsm_compress_finish(AVSM_INOUT(DsmCompressor) c, AVSM_INOUT(DsmTexel) texel) {
  if (c.started && c.previous_depth > c.origin_depth) dsm_end_line(c, c.previous_depth, texel);
}

// ---- A texel's deep shadow map ----

// A texel's build in progress: the exact curve's node being gathered, the list node
// its walk is at, and the compressor.
struct DsmSweep {
  DsmCompressor compressor;
  DsmExactNode exact;
  uint node;
  bool done;
};

DsmSweep dsm_sweep_begin(uint head, float far_depth, float error) {
  DsmSweep sweep;
  sweep.compressor = dsm_compressor_begin(error);
  // A sweep's first walk only finds the first node: its depth is in front of every node.
  sweep.exact = dsm_exact_node_begin(-3.4e38f, far_depth);
  sweep.node = head;
  sweep.done = false;
  return sweep;
}

// Loop passes a list of n segments takes, at most: n + 1 per walk, a walk per node of
// the exact curve (at most 2n + 1) and one more, per sweep (two on the GPU).
uint dsm_sweep_passes(uint segments, uint sweeps) { return sweeps * (2u * segments + 2u) * (segments + 1u); }

// Streams the exact curve of the list from `head` into the compressor, which emits
// the texel's nodes (dsm_emit), as many times as dsm_sweep_again asks; stops after
// `max_passes` loop passes (one list node each: the end of a walk takes the node it
// gathered and starts the next walk), to go on from `sweep` later. The exact curve
// starts at the list's first segment end (1 in front of it) and ends at the far depth;
// an empty list gives one node (far_depth, 1). The subgroup loops in step (a lane
// that has finished idles), as every list walk does (see avsm_resolve.comp).
void dsm_sweep_steps(AVSM_INOUT(DsmSweep) sweep, AVSM_INOUT(DsmTexel) texel, uint head, float far_depth,
                     float error, int max_passes) {
  for (int pass = 0; pass < max_passes; ++pass) {
    if (!subgroupAny(!sweep.done)) break;
    if (sweep.done) continue;
    if (sweep.node != kListEnd) {
      CaptureSegment s = dsm_segment(texel, sweep.node);
      sweep.node = s.next;
      dsm_exact_node_add(sweep.exact, s, far_depth);
      continue;
    }
    DsmExactNode exact = sweep.exact;
    if (exact.depth > -3.4e38f) {
      dsm_compress_node(sweep.compressor, exact.depth, exact.before, texel);
      if (exact.after != exact.before) dsm_compress_node(sweep.compressor, exact.depth, exact.after, texel);
    }
    float next_depth = exact.next_depth;
    if (next_depth >= 3.4e38f) {  // the sweep is complete
      dsm_compress_finish(sweep.compressor, texel);
      sweep.done = !dsm_sweep_again(texel);
      sweep.compressor = dsm_compressor_begin(error);
      next_depth = -3.4e38f;
    }
    sweep.exact = dsm_exact_node_begin(next_depth, far_depth);
    sweep.node = head;
  }
}

#endif
