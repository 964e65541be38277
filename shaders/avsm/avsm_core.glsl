// The AVSM core (Salvi et al., EGSR 2010), written once for GLSL and C++.
//
// A curve is a front-to-back sorted list of nodes (depth, transmittance) that
// describes transmittance along one light ray, linear between nodes, 1 in front
// of the first node and the last node's value behind it. Streaming insertion
// composites one segment at a time and compresses back to `max_nodes` by
// removing the interior node whose removal changes the area under the curve
// least; the first and last nodes are never removed and no node ever moves.
//
// Every loop runs to a constant bound (the curve capacity) with the real condition
// inside: with loop bounds that differ between lanes (a curve's count), lavapipe
// dropped iterations for some lanes after long divergent loops and stored corrupt
// curves. No array is indexed by a value that differs between lanes.
//
// C++ includes this file through passes/shadows/techniques/avsm/avsm_core.h, which defines AVSM_INOUT
// and brings GLSL's built-ins (min, max, abs, mix, exp, pow) in from GLM. Keep
// to the common subset: no GLSL-only syntax, float literals with an f suffix.
#ifndef AVSM_CORE_GLSL
#define AVSM_CORE_GLSL

#ifndef AVSM_INOUT
#define AVSM_INOUT(T) inout T
#endif

// Loops over a curve's slots: unrolled, so that every slot is a register. The compiler
// unrolls short loops by itself (on lavapipe up to 16 iterations) and not the 18 of a
// 16-node curve without being asked. C++ (passes/shadows/techniques/avsm/avsm_core.h) defines it empty.
#ifndef AVSM_UNROLL
#extension GL_EXT_control_flow_attributes : require
#define AVSM_UNROLL [[unroll]]
#endif

// Room for the node count plus the two nodes one insertion adds. Every loop below
// runs over the whole capacity with the real condition inside, so the compiler can
// unroll it and keep the curve in registers; that is what makes insertion fast (on
// lavapipe about 10x at 8 nodes), and it only happens when the capacity is the
// curve's own: shaders built per node count (shaders/CMakeLists.txt) get
// AVSM_NODES. Others may define a capacity (the deep shadow map build: longer
// curves); the default has room for the largest AVSM, 16 nodes.
#if defined(AVSM_NODES) && !defined(AVSM_CURVE_CAPACITY)
#define AVSM_CURVE_CAPACITY (AVSM_NODES + 2)
#endif
#ifndef AVSM_CURVE_CAPACITY
#define AVSM_CURVE_CAPACITY 18
#endif

struct AvsmCurve {
  float depth[AVSM_CURVE_CAPACITY];
  float trans[AVSM_CURVE_CAPACITY];
  int count;
};

// The cleared curve: one node at the far plane with transmittance 1 (the
// course notes' "clear to (far, 1)").
AvsmCurve avsm_clear(float far_depth) {
  AvsmCurve c;
  AVSM_UNROLL for (int i = 0; i < AVSM_CURVE_CAPACITY; ++i) {
    c.depth[i] = far_depth;
    c.trans[i] = 1.0f;
  }
  c.count = 1;
  return c;
}

// Transmittance of the curve at depth d with linear interpolation between nodes.
float avsm_evaluate_linear(AvsmCurve c, float d) {
  float value = c.trans[0];  // behind the last node: its value
  bool found = false;
  AVSM_UNROLL for (int i = 1; i < AVSM_CURVE_CAPACITY; ++i) {
    bool live = i < c.count;
    if (live && !found) {
      if (d < c.depth[i]) {
        float span = c.depth[i] - c.depth[i - 1];
        float t = span > 0.0f ? (d - c.depth[i - 1]) / span : 1.0f;
        value = mix(c.trans[i - 1], c.trans[i], t);
        found = true;
      } else {
        value = c.trans[i];
      }
    }
  }
  return d <= c.depth[0] ? 1.0f : value;
}

// Inserts a node at depth d with the curve's current value there; returns its index.
// The caller multiplies it (and the nodes behind it) by the segment's transmittance.
// Nodes at or in front of d stay, the others move back one slot (walked back to front
// so each slot reads its neighbour before that is overwritten).
int avsm_insert_node(AVSM_INOUT(AvsmCurve) c, float d) {
  float value = avsm_evaluate_linear(c, d);
  int at = 0;
  AVSM_UNROLL for (int i = 0; i < AVSM_CURVE_CAPACITY; ++i)
    if (i < c.count && c.depth[i] <= d) at = i + 1;
  AVSM_UNROLL for (int j = AVSM_CURVE_CAPACITY - 1; j > 0; --j) {
    if (j == at) {
      c.depth[j] = d;
      c.trans[j] = value;
    } else if (j > at && j <= c.count) {
      c.depth[j] = c.depth[j - 1];
      c.trans[j] = c.trans[j - 1];
    }
  }
  if (at == 0) {
    c.depth[0] = d;
    c.trans[0] = value;
  }
  c.count += 1;
  return at;
}

// Area change of removing interior node i: twice the triangle (i-1, i, i+1),
// the paper's |(d[i+1]-d[i-1])(t[i+1]-t[i]) - (d[i+1]-d[i])(t[i+1]-t[i-1])|.
float avsm_removal_cost(AvsmCurve c, int i) {
  return abs((c.depth[i + 1] - c.depth[i - 1]) * (c.trans[i + 1] - c.trans[i]) -
             (c.depth[i + 1] - c.depth[i]) * (c.trans[i + 1] - c.trans[i - 1]));
}

void avsm_remove_node(AVSM_INOUT(AvsmCurve) c, int i) {
  AVSM_UNROLL for (int k = 1; k + 1 < AVSM_CURVE_CAPACITY; ++k) {
    if (k >= i && k + 1 < c.count) {
      c.depth[k] = c.depth[k + 1];
      c.trans[k] = c.trans[k + 1];
    }
  }
  c.count -= 1;
}

// Removes the cheapest interior node (ties: the front-most, so results are
// deterministic) if the curve has more than max_nodes.
void avsm_compress_once(AVSM_INOUT(AvsmCurve) c, int max_nodes) {
  if (c.count <= max_nodes || c.count <= 2) return;
  int cheapest = 1;
  float cheapest_cost = avsm_removal_cost(c, 1);
  AVSM_UNROLL for (int i = 2; i + 1 < AVSM_CURVE_CAPACITY; ++i) {
    if (i + 1 < c.count) {
      float cost = avsm_removal_cost(c, i);
      if (cost < cheapest_cost) {
        cheapest_cost = cost;
        cheapest = i;
      }
    }
  }
  avsm_remove_node(c, cheapest);
}

// Removes the cheapest interior node until at most max_nodes remain.
void avsm_compress(AVSM_INOUT(AvsmCurve) c, int max_nodes) {
  for (int round = 0; round < AVSM_CURVE_CAPACITY; ++round) {
    if (c.count <= max_nodes || c.count <= 2) break;
    avsm_compress_once(c, max_nodes);
  }
}

// Transmittance of one occluding segment at depth d: 1 in front of `entry`,
// falling linearly to `exit_trans` at `exit_depth`, `exit_trans` behind it.
// The exact (uncompressed) curve of a list is the product of these.
float avsm_segment_transmittance(float entry, float exit_depth, float exit_trans, float d) {
  if (d <= entry) return 1.0f;
  if (d >= exit_depth) return exit_trans;
  return mix(1.0f, exit_trans, (d - entry) / (exit_depth - entry));
}

// Composites one occluding segment [entry, exit] whose transmittance falls
// linearly from 1 at entry to exit_trans at exit (the paper's segments; an
// opaque blocker is a short segment with exit_trans 0), then compresses.
void avsm_insert_segment(AVSM_INOUT(AvsmCurve) c, float entry, float exit_depth, float exit_trans, int max_nodes) {
  float far_depth = c.depth[0];  // the last node's depth
  AVSM_UNROLL for (int i = 1; i < AVSM_CURVE_CAPACITY; ++i)
    if (i < c.count) far_depth = c.depth[i];
  entry = min(entry, far_depth);
  exit_depth = min(max(exit_depth, entry), far_depth);
  int first = avsm_insert_node(c, entry);
  int last = avsm_insert_node(c, exit_depth);
  // The entry node keeps its value (the segment starts at 1); nodes inside get
  // the segment's value at their depth, nodes from the exit on its exit value.
  AVSM_UNROLL for (int i = 1; i < AVSM_CURVE_CAPACITY; ++i) {
    if (i < c.count && i > first)
      c.trans[i] *= i >= last ? exit_trans : avsm_segment_transmittance(entry, exit_depth, exit_trans, c.depth[i]);
  }
  // Two nodes came in: two go when the curve was full before (unrolled, so the curve
  // stays in registers), any more only for a curve that came in over max_nodes.
  avsm_compress_once(c, max_nodes);
  avsm_compress_once(c, max_nodes);
  avsm_compress(c, max_nodes);
}

// Appends a node behind every other node and compresses: the streaming
// simplification used to build a mip level from the merged curves of 2x2
// texels. The newest node is the last one, so it is never the one removed.
void avsm_append_node(AVSM_INOUT(AvsmCurve) c, float d, float t, int max_nodes) {
  AVSM_UNROLL for (int j = 0; j < AVSM_CURVE_CAPACITY; ++j) {
    if (j == c.count) {
      c.depth[j] = d;
      c.trans[j] = t;
    }
  }
  c.count += 1;
  avsm_compress(c, max_nodes);
}

// Interpolation between two neighbouring nodes at fraction s: linear, or
// exponential (linear in optical depth, exact inside a homogeneous medium).
float avsm_interpolate(float t0, float t1, float s, bool exponential) {
  if (!exponential || t0 <= 0.0f || t1 <= 0.0f) return mix(t0, t1, s);  // no log of 0: linear
  return t0 * pow(t1 / t0, s);
}

// Curve c (n nodes, sorted) at depth d, given `consumed`: how many of its nodes
// lie at or in front of d. The same value as avsm_evaluate_linear, in O(1) for a
// caller that walks depths front to back.
float avsm_evaluate_at_cursor(AvsmCurve c, int consumed, float d) {
  if (consumed == 0) return 1.0f;
  if (consumed >= c.count) return c.trans[c.count - 1];
  float span = c.depth[consumed] - c.depth[consumed - 1];
  float t = span > 0.0f ? (d - c.depth[consumed - 1]) / span : 1.0f;
  return mix(c.trans[consumed - 1], c.trans[consumed], t);
}

// One mip texel from its 2x2 children: the mean of the four curves, taken at
// every child node depth front to back (a 4-way merge) and streamed into a new
// curve compressed to max_nodes as it grows. Repeated depths (padding, shared
// nodes) are taken once.
AvsmCurve avsm_mip_merge(AvsmCurve c0, AvsmCurve c1, AvsmCurve c2, AvsmCurve c3, int max_nodes) {
  AvsmCurve merged = avsm_clear(0.0f);
  merged.count = 0;
  int k0 = 0, k1 = 0, k2 = 0, k3 = 0;
  float previous = -3.4e38f;
  int total = c0.count + c1.count + c2.count + c3.count;
  for (int step = 0; step < 4 * AVSM_CURVE_CAPACITY; ++step) {
    if (step >= total) break;
    // The next node: the smallest unconsumed depth (ties: the lowest child).
    float d = 3.4e38f;
    int pick = -1;
    if (k0 < c0.count && c0.depth[k0] < d) { d = c0.depth[k0]; pick = 0; }
    if (k1 < c1.count && c1.depth[k1] < d) { d = c1.depth[k1]; pick = 1; }
    if (k2 < c2.count && c2.depth[k2] < d) { d = c2.depth[k2]; pick = 2; }
    if (k3 < c3.count && c3.depth[k3] < d) { d = c3.depth[k3]; pick = 3; }
    // Consume every node at this depth, so each child is evaluated behind it.
    for (int j = 0; j < AVSM_CURVE_CAPACITY; ++j) {
      if (k0 >= c0.count || c0.depth[k0] > d) break;
      ++k0;
    }
    for (int j = 0; j < AVSM_CURVE_CAPACITY; ++j) {
      if (k1 >= c1.count || c1.depth[k1] > d) break;
      ++k1;
    }
    for (int j = 0; j < AVSM_CURVE_CAPACITY; ++j) {
      if (k2 >= c2.count || c2.depth[k2] > d) break;
      ++k2;
    }
    for (int j = 0; j < AVSM_CURVE_CAPACITY; ++j) {
      if (k3 >= c3.count || c3.depth[k3] > d) break;
      ++k3;
    }
    if (pick < 0) break;
    if (d <= previous) continue;
    previous = d;
    float t = 0.25f * (avsm_evaluate_at_cursor(c0, k0, d) + avsm_evaluate_at_cursor(c1, k1, d) +
                       avsm_evaluate_at_cursor(c2, k2, d) + avsm_evaluate_at_cursor(c3, k3, d));
    avsm_append_node(merged, d, t, max_nodes);
  }
  return merged;
}

#endif
