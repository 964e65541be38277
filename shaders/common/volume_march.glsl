// What the camera marches share (common/volume_cached_march.glsl, the fast one, and
// common/volume_reference_march.glsl): the per-ray state, and the walk through every
// volume front to back. The including march defines visit_volume_interval (the steps
// inside one brick's stretch of the ray; common/volume.glsl declares it).
#ifndef AVSM_VOLUME_MARCH_GLSL
#define AVSM_VOLUME_MARCH_GLSL

#extension GL_GOOGLE_include_directive : require

struct MarchState {
  float transmittance;  // camera to the current point
  vec3 in_scattered;    // radiance scattered towards the camera so far
};
#define AVSM_VOLUME_WALK_STATE MarchState
#include "common/volume.glsl"

uint march_volume_count = 0u;
bool march_skip_empty = true;
uint march_volume = 0u;  // the volume being walked

// Below this the rest of the ray cannot change the pixel visibly (it would add
// at most 1e-3 of the remaining light), so the march stops.
const float kMinTransmittance = 1e-3;

// Continues `state` along the world ray over [t_min, t_max] through every volume,
// front to back by entry distance; transmittance carries from one to the next.
// `touched`: whether that stretch met any volume.
MarchState march_ray_between(vec3 origin, vec3 direction, float t_min, float t_max, MarchState state,
                             out bool touched) {
  touched = false;
  float previous_enter = -1.0;
  int previous_index = -1;
  uint v;
  float t_enter, t_exit;
  while (state.transmittance >= kMinTransmittance &&
         next_volume(march_volume_count, origin, direction, t_min, t_max, previous_enter, previous_index, v, t_enter,
                     t_exit)) {
    march_volume = v;
    walk_volume_bricks(v, origin, direction, t_enter, t_exit, march_skip_empty, state);
    touched = true;
    previous_enter = t_enter;
    previous_index = int(v);
  }
  return state;
}

// Marches the world ray [0, t_max] through every volume front to back.
MarchState march_ray(vec3 origin, vec3 direction, float t_max, out bool touched) {
  return march_ray_between(origin, direction, 0.0, t_max, MarchState(1.0, vec3(0.0)), touched);
}

#endif
