// Deep shadow maps (Lokovic & Veach 2000): a texel's exact transmittance curve,
// compressed to as few nodes as keep it within a user error everywhere, with a
// variable node count per texel. Written for GLSL and C++ like the AVSM core
// (include avsm/avsm_core.glsl first; C++ through passes/deep_shadow.h).
#ifndef AVSM_DEEP_SHADOW_GLSL
#define AVSM_DEEP_SHADOW_GLSL

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

// Lokovic & Veach's greedy compression: from the last emitted node (the origin),
// follow the exact curve's nodes while one line from the origin stays within
// `error` of every one of them (a narrowing range of slopes); when no slope fits the next
// node, emit the line's end at the previous node and start again from there. A
// jump at one depth (an opaque surface) that exceeds the error becomes two nodes
// at that depth. The compressed curve is within `error` of the exact one at each
// of its nodes, so everywhere: its nodes sit at exact-curve node depths, so both
// are linear between those. `compressed` holds at most as many nodes as `exact`.
void dsm_compress(AvsmCurve exact, float error, AVSM_INOUT(AvsmCurve) compressed) {
  compressed.count = 0;
  if (exact.count == 0) return;
  float origin_depth = exact.depth[0], origin_trans = exact.trans[0];
  compressed.depth[0] = origin_depth;
  compressed.trans[0] = origin_trans;
  compressed.count = 1;
  float low = -3.4e38f, high = 3.4e38f;  // slopes that keep every node so far within the error
  int i = 1;
  // Each pass of the loop consumes a node or emits one before consuming it: at most
  // two passes per node (a constant bound, as in the AVSM core).
  for (int pass = 0; pass < 2 * AVSM_CURVE_CAPACITY; ++pass) {
    if (i >= exact.count) break;
    float dz = exact.depth[i] - origin_depth;
    if (dz <= 1e-7f) {  // same depth as the origin: a step
      if (abs(exact.trans[i] - origin_trans) > error) {
        origin_trans = exact.trans[i];
        compressed.depth[compressed.count] = origin_depth;
        compressed.trans[compressed.count] = origin_trans;
        compressed.count += 1;
        low = -3.4e38f;
        high = 3.4e38f;
      }
      i += 1;
      continue;
    }
    float new_low = max(low, (exact.trans[i] - error - origin_trans) / dz);
    float new_high = min(high, (exact.trans[i] + error - origin_trans) / dz);
    if (new_low <= new_high) {
      low = new_low;
      high = new_high;
      i += 1;
      continue;
    }
    // Node i does not fit: end the line at the previous node.
    float end_depth = exact.depth[i - 1];
    origin_trans += dsm_line_slope(low, high, origin_depth, origin_trans, end_depth) * (end_depth - origin_depth);
    origin_depth = end_depth;
    compressed.depth[compressed.count] = origin_depth;
    compressed.trans[compressed.count] = origin_trans;
    compressed.count += 1;
    low = -3.4e38f;
    high = 3.4e38f;
  }
  // The last line ends at the last exact node.
  float last_depth = exact.depth[exact.count - 1];
  if (last_depth > origin_depth) {
    compressed.depth[compressed.count] = last_depth;
    compressed.trans[compressed.count] =
        origin_trans + dsm_line_slope(low, high, origin_depth, origin_trans, last_depth) * (last_depth - origin_depth);
    compressed.count += 1;
  }
}

#endif
