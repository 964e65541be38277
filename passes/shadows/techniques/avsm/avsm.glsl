// AVSM lookups: a texel's N-node curve in the light's map (layout: shared/map_layouts.h,
// packed nodes decoded by its avsm_node_* functions), searched two levels deep (the
// course notes' 4-stride search): the last depth of each vec4 first, then inside the
// vec4 that holds the answer. Included by common/shadow_lookup.glsl through the
// generated dispatch.
#ifndef AVSM_TECHNIQUE_AVSM_GLSL
#define AVSM_TECHNIQUE_AVSM_GLSL

// First vec4 of a texel's curve in its light's map.
uint avsm_texel_base(GpuShadow s, uint level, ivec2 texel) {
  return avsm_map_texel_base(s.resolution, s.node_count, level, uint(texel.x), uint(texel.y));
}

// Four packed nodes of a texel (vec4 i of the light's map).
uvec4 avsm_texel_nodes(GpuShadow s, uint i) { return floatBitsToUint(shadow_map_texel(s, i)); }

float avsm_texel_node_depth(GpuShadow s, uint node) {
  return avsm_node_depth(node, s.depth_range.x, s.depth_range.y);
}

// One texel's stored curve at depth d; the same answer as avsm_evaluate_linear on
// the stored nodes (the padding nodes are never "the first node behind d").
float avsm_texel_transmittance(GpuShadow s, uint base, float d) {
  uint groups = s.node_count / 4u;
  uvec4 nodes = uvec4(0u);
  uint g = 0u;
  for (; g < 4u; ++g) {  // constant bounds in the lookups: see avsm_core.glsl
    if (g >= groups) break;
    nodes = avsm_texel_nodes(s, base + g);
    if (d < avsm_texel_node_depth(s, nodes.w)) break;
  }
  if (g == groups) return avsm_node_transmittance(nodes.w);  // behind every node: the last group's last
  vec3 depths = vec3(avsm_texel_node_depth(s, nodes.x), avsm_texel_node_depth(s, nodes.y),
                     avsm_texel_node_depth(s, nodes.z));
  uint k = d < depths.x ? 0u : (d < depths.y ? 1u : (d < depths.z ? 2u : 3u));
  if (g == 0u && k == 0u) return 1.0;  // in front of the first node
  uint node1 = nodes[k];
  uint node0 = k > 0u ? nodes[k - 1u] : avsm_texel_nodes(s, base + g - 1u).w;
  float d1 = avsm_texel_node_depth(s, node1), d0 = avsm_texel_node_depth(s, node0);
  float t1 = avsm_node_transmittance(node1), t0 = avsm_node_transmittance(node0);
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
  float previous_depth = far_depth;
  for (uint i = 0u; i < s.node_count; ++i) {
    uint node = avsm_texel_nodes(s, base + i / 4u)[i % 4u];
    float depth = avsm_texel_node_depth(s, node);
    if (avsm_node_transmittance(node) <= kShadowOpaque) return i == 0u ? depth : previous_depth;
    previous_depth = depth;
  }
  return far_depth;
}

#endif
