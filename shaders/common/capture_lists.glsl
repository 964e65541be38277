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

// The head of map texel `texel` of a view whose lists are `tile` of the head image
// (x: its first texel, y: its texels per row; LightView::list_tile()): its texels
// follow one another row by row from tile.x, laid on the image's rows. A view with
// lists of its own (tile (0, image width)) keeps its texels where they are; an area
// light's virtual lights share one image, each a range of its texels (and so of the
// map built from it).
ivec2 capture_head_texel(ivec2 texel, uvec2 tile) {
  uint width = uint(imageSize(capture_heads).x);
  uint index = tile.x + uint(texel.y) * tile.y + uint(texel.x);
  return ivec2(index % width, index / width);
}

// Appends a segment to the list of `texel` of the view whose tile is `tile`. When the
// node buffer is full the segment is counted (so the next frame can grow the buffer)
// and dropped: no write goes out of bounds and the list stays well formed, only
// lighter than it should be.
void capture_append(ivec2 texel, uvec2 tile, float entry, float exit_depth, float exit_trans) {
  uint index = atomicAdd(capture_count, 1u);
  if (index >= uint(capture_nodes.length())) return;
  uint previous = imageAtomicExchange(capture_heads, capture_head_texel(texel, tile), index);
  capture_nodes[index] = CaptureSegment(entry, exit_depth, exit_trans, previous);
}
#endif

// Lists are walked from the head. As captured, `next` always points at an older node
// (a smaller index); the sort (capture_sort.comp) relinks them front to back.
// Either way a list ends at kListEnd.
#endif
