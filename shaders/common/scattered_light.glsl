// Radiance that the lights scatter towards the camera at a point in smoke, per unit
// sigma_s, every light's map looked up. The lighting cache stores it per cell; the
// reference march, and the fast march inside a volume without cache, evaluate it
// along the ray. The includer has included common/volume.glsl (phase_function),
// common/lights.glsl and common/shadow_lookup.glsl, and declared `lights`.
#ifndef AVSM_SCATTERED_LIGHT_GLSL
#define AVSM_SCATTERED_LIGHT_GLSL

vec3 scattered_light(vec3 p, vec3 to_camera, uint light_count) {
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < light_count; ++i) {
    vec3 to_light;
    vec3 radiance = light_radiance(lights[i], p, to_light);
    sum += radiance * phase_function(to_camera, to_light) * volume_light_transmittance(i, p);
  }
  return sum;
}

#endif
