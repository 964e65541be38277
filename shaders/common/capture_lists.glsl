// Per-pixel segment lists of a light's capture (the paper's light-space "fragment
// lists"): a head-pointer image with one list per texel and a node buffer the
// captures append to with one atomic counter.
//
// Before including, define AVSM_CAPTURE_BINDING: the head image is at that
// binding, the node buffer at +1 and the counter at +2. Define
// AVSM_CAPTURE_APPEND in the passes that append (they get capture_append());
// the others only walk the lists, read-only unless they define
// AVSM_CAPTURE_HEAD_ACCESS and AVSM_CAPTURE_NODE_ACCESS (empty, for the sort that
// relinks the lists).
#ifndef AVSM_CAPTURE_LISTS_GLSL
#define AVSM_CAPTURE_LISTS_GLSL

#extension GL_GOOGLE_include_directive : require
#include "shared/capture.h"

#ifndef AVSM_CAPTURE_APPEND
#ifndef AVSM_CAPTURE_HEAD_ACCESS
#define AVSM_CAPTURE_HEAD_ACCESS readonly
#endif
#ifndef AVSM_CAPTURE_NODE_ACCESS
#define AVSM_CAPTURE_NODE_ACCESS readonly
#endif
layout(binding = AVSM_CAPTURE_BINDING, r32ui) uniform AVSM_CAPTURE_HEAD_ACCESS uimage2D capture_heads;
layout(std430, binding = AVSM_CAPTURE_BINDING + 1) AVSM_CAPTURE_NODE_ACCESS buffer CaptureNodes {
  CaptureSegment capture_nodes[];
};
#else
layout(binding = AVSM_CAPTURE_BINDING, r32ui) uniform coherent uimage2D capture_heads;
layout(std430, binding = AVSM_CAPTURE_BINDING + 1) buffer CaptureNodes { CaptureSegment capture_nodes[]; };
// count: nodes asked for this frame, including those that did not fit.
layout(std430, binding = AVSM_CAPTURE_BINDING + 2) buffer CaptureCounter { uint capture_count; };

// Appends a segment to the list of `texel`. When the node buffer is full the
// segment is counted (so the next frame can grow the buffer) and dropped: no write
// goes out of bounds and the list stays well formed, only lighter than it should be.
void capture_append(ivec2 texel, float entry, float exit_depth, float exit_trans) {
  uint index = atomicAdd(capture_count, 1u);
  if (index >= uint(capture_nodes.length())) return;
  uint previous = imageAtomicExchange(capture_heads, texel, index);
  capture_nodes[index] = CaptureSegment(entry, exit_depth, exit_trans, previous);
}
#endif

// Lists are walked from the head. As captured, `next` always points at an older node
// (a smaller index); the sort (capture_sort.comp) relinks them front to back.
// Either way a list ends at kListEnd.
#endif
