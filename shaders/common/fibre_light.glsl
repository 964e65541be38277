// Light reaching a hair fibre: Kajiya-Kay diffuse (light scatters by the sine of the
// angle to the tangent) from every light, shadowed through its map, plus the sky.
// Per vertex in the fast path (common/hair_lighting.glsl), per fragment in the
// reference (hair_reference.frag). The includer has included common/lights.glsl and
// common/shadow_lookup.glsl, and declared `lights`.
#ifndef AVSM_FIBRE_LIGHT_GLSL
#define AVSM_FIBRE_LIGHT_GLSL

vec3 fibre_light(vec3 p, vec3 tangent, uint light_count) {
  vec3 lit = kSkyAmbient;
  for (uint i = 0u; i < light_count; ++i) {
    vec3 to_light;
    vec3 radiance = light_radiance(lights[i], p, to_light);
    float sin_tl = sqrt(max(1.0 - dot(tangent, to_light) * dot(tangent, to_light), 0.0));
    lit += radiance * sin_tl * light_transmittance(i, p);
  }
  return lit;
}

#endif
