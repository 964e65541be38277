// AVSM lookups: a texel's N-node curve in the light's map (layout: shared/map_layouts.h),
// searched two levels deep (the course notes' 4-stride search): the last depth of each
// vec4 first, then inside the vec4 that holds the answer. Included by
// common/shadow_lookup.glsl through the generated dispatch.
#ifndef AVSM_TECHNIQUE_AVSM_GLSL
#define AVSM_TECHNIQUE_AVSM_GLSL

// First vec4 of a texel's curve in its light's map.
uint avsm_texel_base(GpuShadow s, uint level, ivec2 texel) {
  return avsm_map_texel_base(s.resolution, s.node_count, level, uint(texel.x), uint(texel.y));
}

// One texel's stored curve at depth d; the same answer as avsm_evaluate_linear on
// the curve the resolve built (the padding nodes are never "the first node behind d").
float avsm_texel_transmittance(GpuShadow s, uint base, float d) {
  uint slot = s.slot;
  uint groups = s.node_count / 4u;
  vec4 depths = vec4(0.0);
  uint g = 0u;
  for (; g < 4u; ++g) {  // constant bounds in the lookups: see avsm_core.glsl
    if (g >= groups) break;
    depths = shadow_map_texel(slot, base + g);
    if (d < depths.w) break;
  }
  if (g == groups) return shadow_map_texel(slot, base + 2u * groups - 1u).w;  // behind every node
  uint k = d < depths.x ? 0u : (d < depths.y ? 1u : (d < depths.z ? 2u : 3u));
  uint i = 4u * g + k;
  if (i == 0u) return 1.0;  // in front of the first node
  float d1 = depths[k];
  float d0 = k > 0u ? depths[k - 1u] : shadow_map_texel(slot, base + g - 1u).w;
  vec4 transmittances = shadow_map_texel(slot, base + groups + g);
  float t1 = transmittances[k];
  float t0 = k > 0u ? transmittances[k - 1u] : shadow_map_texel(slot, base + groups + g - 1u).w;
  float f = d1 > d0 ? (d - d0) / (d1 - d0) : 1.0;
  return avsm_interpolate(t0, t1, f, s.exponential != 0u);
}

float avsm_lookup(GpuShadow s, uint level, ivec2 texel, float d) {
  return avsm_texel_transmittance(s, avsm_texel_base(s, level, texel), d);
}

// Where the first opaque blocker starts (the light's debug image): the node before the
// first node at ~0 transmittance; the far depth when there is none.
#define AVSM_AVSM_FIRST_OPAQUE_DEPTH
float avsm_first_opaque_depth(GpuShadow s, ivec2 texel) {
  float far_depth = s.texel_camera.z;
  uint base = avsm_texel_base(s, 0u, texel);
  uint groups = s.node_count / 4u;
  float previous_depth = far_depth;
  for (uint i = 0u; i < s.node_count; ++i) {
    float depth = shadow_map_texel(s.slot, base + i / 4u)[i % 4u];
    float trans = shadow_map_texel(s.slot, base + groups + i / 4u)[i % 4u];
    if (trans <= kShadowOpaque) return i == 0u ? depth : previous_depth;
    previous_depth = depth;
  }
  return far_depth;
}

#endif
