// Transmittance from light `light_index` to world point `p`: the one place
// every shading pass asks about shadows. Returns 1 (unshadowed) until the AVSM
// passes land and this becomes the shadow-map lookup.
#ifndef AVSM_SHADOW_LOOKUP_GLSL
#define AVSM_SHADOW_LOOKUP_GLSL

float light_transmittance(uint light_index, vec3 p) { return 1.0; }

#endif
