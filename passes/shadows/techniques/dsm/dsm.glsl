// Deep shadow map lookups (layout: shared/map_layouts.h).
#ifndef AVSM_TECHNIQUE_DSM_GLSL
#define AVSM_TECHNIQUE_DSM_GLSL

// Deep shadow map texel (layout: shared/map_layouts.h): its own count of
// nodes in the shared pool, front to back.
uint dsm_word(GpuShadow s, uint word) { return floatBitsToUint(shadow_map_texel(s, word >> 2u)[word & 3u]); }

// Pool node `node` as (depth, transmittance). A node is two words at an even word of
// a pool that starts on a vec4: one vec4 half.
vec2 dsm_node(GpuShadow s, uint node) {
  uint word = dsm_pool_base(s.resolution) + 2u * node;
  vec4 pair = shadow_map_texel(s, word >> 2u);
  return uintBitsToFloat(floatBitsToUint((word & 2u) == 0u ? pair.xy : pair.zw));
}

float dsm_lookup(GpuShadow s, uint level, ivec2 texel, float d) {
  uint index = uint(texel.y) * s.resolution + uint(texel.x);
  uint first = dsm_word(s, dsm_first_node_word(index)), count = dsm_word(s, dsm_node_count_word(index));
  // A texel the full pool could not take (counted and reported; the pool grows for the next frame).
  if (count == 0u || count == kDsmLost) return 1.0;
  // Binary search for the nodes at or in front of d, [0, behind): a texel may hold
  // thousands. The loop bound is constant (see avsm_core.glsl): 32 halvings end any search.
  uint behind = 0u, end = count;
  for (int step = 0; step < 32; ++step) {
    if (behind >= end) break;
    uint middle = (behind + end) / 2u;
    if (dsm_node(s, first + middle).x <= d) {
      behind = middle + 1u;
    } else {
      end = middle;
    }
  }
  if (behind == 0u) return 1.0;
  vec2 previous = dsm_node(s, first + behind - 1u);
  if (behind == count) return clamp(previous.y, 0.0, 1.0);
  vec2 next = dsm_node(s, first + behind);
  float f = (d - previous.x) / (next.x - previous.x);  // previous.x <= d < next.x
  // Lokovic-Veach nodes may lie up to the error outside [0, 1].
  return clamp(avsm_interpolate(previous.y, next.y, f, s.exponential != 0u), 0.0, 1.0);
}

// Where the first opaque blocker along the texel's ray starts (for the maps' pictures,
// shaders/passes/shadows/inspection/shadow_debug.comp): the node before the first opaque one, as for AVSM.
// Opaque: at most 0.05, as compressed nodes lie up to the error away from the exact 0.
#define AVSM_DSM_FIRST_OPAQUE_DEPTH
float dsm_first_opaque_depth(GpuShadow s, ivec2 texel) {
  float far_depth = s.texel_camera.z;
  uint index = uint(texel.y) * s.resolution + uint(texel.x);
  uint first = dsm_word(s, dsm_first_node_word(index)), count = dsm_word(s, dsm_node_count_word(index));
  if (count == kDsmLost) return far_depth;
  float previous_depth = far_depth;
  for (uint k = 0u; k < 65536u; ++k) {  // constant bound (see avsm_core.glsl); a texel has fewer nodes
    if (k >= count) break;
    vec2 node = dsm_node(s, first + k);
    // Just in front of the node before: where that node and the opaque one share a depth
    // (a step), a lookup at the depth itself reads the value behind the step.
    if (node.y <= 0.05) return k == 0u ? node.x : previous_depth - 1e-5 * max(abs(previous_depth), 1.0);
    previous_depth = node.x;
  }
  return far_depth;
}

#endif
