// Deep shadow map lookups (layout: shared/map_layouts.h).
#ifndef AVSM_TECHNIQUE_DSM_GLSL
#define AVSM_TECHNIQUE_DSM_GLSL

// Deep shadow map texel (layout: shared/map_layouts.h): its own count of
// nodes in the shared pool, searched front to back.
uint dsm_word(GpuShadow s, uint word) { return floatBitsToUint(shadow_map_texel(s, word >> 2u)[word & 3u]); }

float dsm_lookup(GpuShadow s, uint level, ivec2 texel, float d) {
  uint index = uint(texel.y) * s.resolution + uint(texel.x);
  uint first = dsm_word(s, dsm_first_node_word(index)), count = dsm_word(s, dsm_node_count_word(index));
  // A texel the full pool could not take (counted and reported; the pool grows for the next frame).
  if (count == 0u || count == kDsmLost) return 1.0;
  uint pool = dsm_pool_base(s.resolution);
  float previous_depth = 0.0, previous_trans = 1.0;
  for (uint k = 0u; k < uint(AVSM_CURVE_CAPACITY); ++k) {  // at most the build's curve capacity
    if (k >= count) break;
    // A node is two words at an even word of a pool that starts on a vec4: one vec4 half.
    uint word = pool + 2u * (first + k);
    vec4 pair = shadow_map_texel(s, word >> 2u);
    vec2 node = uintBitsToFloat(floatBitsToUint((word & 2u) == 0u ? pair.xy : pair.zw));
    float depth = node.x, trans = node.y;
    if (d < depth) {
      if (k == 0u) return 1.0;
      float f = depth > previous_depth ? (d - previous_depth) / (depth - previous_depth) : 1.0;
      // Lokovic-Veach nodes may lie up to the error outside [0, 1].
      return clamp(avsm_interpolate(previous_trans, trans, f, s.exponential != 0u), 0.0, 1.0);
    }
    previous_depth = depth;
    previous_trans = trans;
  }
  return clamp(previous_trans, 0.0, 1.0);
}

#endif
