// Radiance that the lights and the sky scatter towards the camera at a point in smoke, per
// unit sigma_s, every light's map looked up. The lighting cache stores it per cell; the
// reference march, and the fast march inside a volume without cache, evaluate it
// along the ray. The includer has included common/volume.glsl (phase_function,
// sky_lighting), common/lights.glsl and common/shadow_lookup.glsl, and declared `lights`.
//
// Multiple scattering is approximated by octaves of single scattering
// (scene::MultipleScattering, after Wrenninge et al. 2013): octave k sees the optical depth
// towards the light scaled by attenuation^k, so transmittance^(attenuation^k), and carries
// (contribution * albedo * (1 - escape))^k of the light, escape being the chance that light
// scattered there leaves the volume unscattered. Every light's one map lookup serves all
// octaves.
// The sky is uniform (kSkyAmbient) and reaches the point through the volume itself; with
// an isotropic phase its in-scattered radiance is the sky's times the mean transmittance
// over the sphere, octave by octave as for the lights, summed on the CPU per brick corner
// (sky_lighting).
#ifndef AVSM_SCATTERED_LIGHT_GLSL
#define AVSM_SCATTERED_LIGHT_GLSL

// How many octaves a volume scatters in; a host's volume may leave 0, which means 1.
uint scattering_octave_count(GpuVolume volume) { return clamp(volume.octaves, 1u, 8u); }

// What carries from one octave to the next: a photon scattered at the point scatters
// again with probability albedo * (1 - escape), escape being the chance that it leaves
// the volume first (sky_lighting's a). So thin smoke gains little and a dense, bright
// core gains much.
vec3 octave_weight(GpuVolume volume, float escape) {
  if (scattering_octave_count(volume) < 2u) return vec3(0.0);
  return volume.octave_contribution * volume.albedo * (1.0 - escape);
}

// Octave k sees transmittance^(attenuation^k) and carries octave_weight^k.
vec3 scattering_octaves(GpuVolume volume, vec3 carried, float transmittance) {
  vec3 sum = vec3(0.0), weight = vec3(1.0);
  float exponent = 1.0;
  uint octaves = scattering_octave_count(volume);
  for (uint k = 0u; k < 8u; ++k) {  // constant bound, break on the count (lavapipe)
    if (k >= octaves) break;
    sum += weight * pow(max(transmittance, 0.0), exponent);
    weight *= carried;
    exponent *= volume.octave_attenuation;
  }
  return sum;
}

// At world point `p`, index position `index_position` of volume `v`.
vec3 scattered_light(uint v, vec3 index_position, vec3 p, vec3 to_camera, uint light_count) {
  GpuVolume volume = volumes[v];
  vec4 sky = sky_lighting(volume, index_position);
  vec3 carried = octave_weight(volume, sky.a);
  vec3 sum = kSkyAmbient * volume.sky_light * sky.rgb;
  for (uint i = 0u; i < light_count; ++i) {
    vec3 to_light;
    vec3 radiance = light_radiance(lights[i], p, to_light);
    sum += radiance * phase_function(to_camera, to_light) *
           scattering_octaves(volume, carried, volume_light_transmittance(i, p));
  }
  return sum;
}

#endif
