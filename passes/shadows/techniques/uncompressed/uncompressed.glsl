// The exact reference's lookup: the light's capture list walked at lookup time.
#ifndef AVSM_TECHNIQUE_UNCOMPRESSED_GLSL
#define AVSM_TECHNIQUE_UNCOMPRESSED_GLSL

// The exact curve of one texel's capture list: the product of its segments.
float uncompressed_lookup(GpuShadow s, uint level, ivec2 texel, float d) {
  float t = 1.0;
  uint node = shadow_list_head(s, texel);
  for (uint steps = 0u; shadow_list_goes_on(node, steps); ++steps) {
    CaptureSegment n = shadow_list_node(s, node);
    t *= avsm_segment_transmittance(n.entry, n.exit_depth, n.exit_trans, d);
    node = n.next;
  }
  return t;
}

// Where the first opaque blocker starts (the light's debug image): the smallest entry
// of a segment ending at ~0; the far depth when there is none.
#define AVSM_UNCOMPRESSED_FIRST_OPAQUE_DEPTH
float uncompressed_first_opaque_depth(GpuShadow s, ivec2 texel) {
  float nearest = s.texel_camera.z;
  uint node = shadow_list_head(s, texel);
  for (uint steps = 0u; shadow_list_goes_on(node, steps); ++steps) {
    CaptureSegment n = shadow_list_node(s, node);
    if (n.exit_trans <= kShadowOpaque) nearest = min(nearest, n.entry);
    node = n.next;
  }
  return nearest;
}

#endif
