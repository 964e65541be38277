#version 460
// Optional per-texel sort of a light's capture lists, front to back by
// (entry, exit, transmittance): the resolve then sees segments in the same order
// every run, so its compressed curve is the same bit for bit whatever order the
// rasteriser and the atomics produced. Payloads move; links stay.
#extension GL_GOOGLE_include_directive : require
#define AVSM_CAPTURE_BINDING 0
#define AVSM_CAPTURE_NODE_ACCESS
#include "common/capture_lists.glsl"

layout(local_size_x = 8, local_size_y = 8) in;
#include "shared/passes/capture_sort.h"

// Lists up to this long are sorted in registers; longer ones in place in memory.
const int kLocalCapacity = 32;

bool before(vec3 a, vec3 b) {
  if (a.x != b.x) return a.x < b.x;
  if (a.y != b.y) return a.y < b.y;
  return a.z < b.z;
}

vec3 payload(uint node) {
  CaptureSegment s = capture_nodes[node];
  return vec3(s.entry, s.exit_depth, s.exit_trans);
}

void store(uint node, vec3 p) {
  capture_nodes[node].entry = p.x;
  capture_nodes[node].exit_depth = p.y;
  capture_nodes[node].exit_trans = p.z;
}

// Selection sort along the chain, for lists that do not fit in registers.
void sort_in_memory(uint head) {
  for (uint i = head; i != kListEnd; i = capture_nodes[i].next) {
    uint smallest = i;
    vec3 smallest_payload = payload(i);
    for (uint j = capture_nodes[i].next; j != kListEnd; j = capture_nodes[j].next) {
      vec3 p = payload(j);
      if (before(p, smallest_payload)) {
        smallest = j;
        smallest_payload = p;
      }
    }
    if (smallest != i) {
      store(smallest, payload(i));
      store(i, smallest_payload);
    }
  }
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.resolution)))) return;
  uint head = imageLoad(capture_heads, texel).r;
  vec3 values[kLocalCapacity];
  uint nodes[kLocalCapacity];
  int count = 0;
  for (uint n = head; n != kListEnd; n = capture_nodes[n].next) {
    if (count == kLocalCapacity) {
      sort_in_memory(head);
      return;
    }
    // Insertion sort while walking.
    vec3 p = payload(n);
    int at = count;
    while (at > 0 && before(p, values[at - 1])) {
      values[at] = values[at - 1];
      --at;
    }
    values[at] = p;
    nodes[count] = n;
    ++count;
  }
  for (int i = 0; i < count; ++i) store(nodes[i], values[i]);
}
