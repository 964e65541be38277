#version 460
// Optional per-texel sort of a light's capture lists, front to back by
// (entry, exit, transmittance): the resolve then sees segments in the same order
// every run, so its compressed curve is the same bit for bit whatever order the
// rasteriser and the atomics produced. Nodes stay where they are; the sort relinks
// them (their `next` and the texel's head).
//
// A bottom-up merge sort of the linked list (S. Tatham's): pass after pass merges
// neighbouring sorted runs of `run` nodes into runs of 2 `run`, about 1.5 n log2(n)
// steps for n segments. Why not something simpler: lavapipe (llvmpipe) ends every loop
// of a shader invocation once all its loops together have iterated 65535 times
// (LP_MAX_TGSI_LOOP_ITERATIONS, one budget per batch of 8 lanes). The selection sort
// this replaces took n^2 / 2 steps and stopped part way on the hair's long lists
// (the default scene's sun at 32^2: lists of 63 to 1,307 segments sorted only at the
// front), so their curves depended on the append order again. Here the steps run as
// one flat state machine, kStepsPerIteration per loop iteration (unrolled, so they
// do not count), and the lanes of a subgroup loop together (a lane whose list is
// sorted idles), as the resolve walks its lists. Lists longer than kMaxSortedSegments
// stay in capture order (still whole, only not front to back): a longer one could run
// out of lavapipe's budget part way through relinking.
#extension GL_GOOGLE_include_directive : require
#extension GL_KHR_shader_subgroup_vote : require
#extension GL_EXT_control_flow_attributes : require
#define AVSM_CAPTURE_BINDING 0
#define AVSM_CAPTURE_HEAD_ACCESS
#define AVSM_CAPTURE_NODE_ACCESS
#include "common/capture_lists.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/passes/shadows/capture/capture_sort.h"

const int kStepsPerIteration = 8;
// Counting and sorting 16,384 segments take about 45,000 loop iterations (sorting
// 22,000 ran out of the budget).
const uint kMaxSortedSegments = 16384u;

bool before(vec3 a, vec3 b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

vec3 payload(uint node) {
  CaptureSegment s = capture_nodes[node];
  return vec3(s.entry, s.exit_depth, s.exit_trans);
}

// What a step does next.
const int kStartMerge = 0;     // p starts the next two runs, or is kListEnd: the pass is over
const int kFindSecondRun = 1;  // walking q to the end of p's run
const int kMerge = 2;          // taking the smaller front of the two runs
const int kSorted = 3;

// One texel's sort in progress.
struct MergeSort {
  int phase;
  uint run;       // nodes per run this pass
  uint merges;    // this pass's so far
  uint merged;    // the head of the list this pass builds
  uint tail;      // its last node, kListEnd while it is empty
  uint p, q;      // the fronts of the two runs being merged
  uint p_left, q_left;  // nodes left in them (q's run may end at kListEnd first)
  vec3 p_value, q_value;  // their payloads
};

MergeSort merge_sort_begin(uint head) {
  MergeSort m;
  m.phase = head == kListEnd ? kSorted : kStartMerge;
  m.run = 1u;
  m.merges = 0u;
  m.merged = kListEnd;
  m.tail = kListEnd;
  m.p = head;
  m.q = kListEnd;
  m.p_left = 0u;
  m.q_left = 0u;
  m.p_value = vec3(0.0);
  m.q_value = vec3(0.0);
  return m;
}

void merge_sort_start_merge(inout MergeSort m) {
  if (m.p != kListEnd) {
    m.merges += 1u;
    m.q = m.p;
    m.p_left = 0u;
    m.phase = kFindSecondRun;
    return;
  }
  // The pass is over. One merge made the whole list one run: sorted.
  capture_nodes[m.tail].next = kListEnd;
  if (m.merges <= 1u) {
    m.phase = kSorted;
    return;
  }
  m.p = m.merged;
  m.merged = kListEnd;
  m.tail = kListEnd;
  m.merges = 0u;
  m.run *= 2u;
}

void merge_sort_find_second_run(inout MergeSort m) {
  m.p_left += 1u;
  m.q = capture_nodes[m.q].next;
  if (m.q != kListEnd && m.p_left < m.run) return;
  m.q_left = m.run;
  m.p_value = payload(m.p);
  if (m.q != kListEnd) m.q_value = payload(m.q);
  m.phase = kMerge;
}

// Appends the smaller front (p's on ties: stable) to the merged list.
void merge_sort_merge(inout MergeSort m) {
  bool q_done = m.q_left == 0u || m.q == kListEnd;
  if (m.p_left == 0u && q_done) {
    m.p = m.q;  // the next two runs start there
    m.phase = kStartMerge;
    return;
  }
  bool take_p = m.p_left > 0u && (q_done || !before(m.q_value, m.p_value));
  uint taken;
  if (take_p) {
    taken = m.p;
    m.p = capture_nodes[m.p].next;
    m.p_left -= 1u;
    if (m.p_left > 0u) m.p_value = payload(m.p);
  } else {
    taken = m.q;
    m.q = capture_nodes[m.q].next;
    m.q_left -= 1u;
    if (m.q_left > 0u && m.q != kListEnd) m.q_value = payload(m.q);
  }
  if (m.tail == kListEnd)
    m.merged = taken;
  else
    capture_nodes[m.tail].next = taken;
  m.tail = taken;
}

void merge_sort_step(inout MergeSort m) {
  if (m.phase == kStartMerge)
    merge_sort_start_merge(m);
  else if (m.phase == kFindSecondRun)
    merge_sort_find_second_run(m);
  else if (m.phase == kMerge)
    merge_sort_merge(m);
}

// Whether the list from `head` holds 2 to kMaxSortedSegments segments (the lanes count together).
bool worth_sorting(uint head) {
  uint node = head, length = 0u;
  while (subgroupAny(node != kListEnd && length <= kMaxSortedSegments)) {
    [[unroll]] for (int k = 0; k < kStepsPerIteration; ++k) {
      if (node != kListEnd && length <= kMaxSortedSegments) {
        node = capture_nodes[node].next;
        length += 1u;
      }
    }
  }
  return length >= 2u && length <= kMaxSortedSegments;
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.resolution)))) return;
  uint head = imageLoad(capture_heads, texel).r;
  bool sort = worth_sorting(head);
  MergeSort m = merge_sort_begin(sort ? head : kListEnd);
  while (subgroupAny(m.phase != kSorted)) {
    [[unroll]] for (int k = 0; k < kStepsPerIteration; ++k) merge_sort_step(m);
  }
  if (sort && m.merged != head) imageStore(capture_heads, texel, uvec4(m.merged));
}
