// The fast camera march: density from the brick atlas (one hardware-trilinear fetch
// per sample) and in-scattering from the lighting cache (one more), no shadow-map
// lookups along the ray, and steps of march_step_voxels voxels. Shared by the camera
// march (volume_cached_march.comp) and the hair's per-vertex fog (hair_lighting.comp).
//
// Before including, define the volume bindings (common/volume.glsl, atlas included)
// and AVSM_CACHE_BINDING (common/volume_lighting_cache.glsl). Set march_volume_count,
// march_step_voxels and march_skip_empty before marching.
#ifndef AVSM_VOLUME_CACHED_MARCH_GLSL
#define AVSM_VOLUME_CACHED_MARCH_GLSL

#extension GL_GOOGLE_include_directive : require

struct MarchState {
  float transmittance;  // camera to the current point
  vec3 in_scattered;    // radiance scattered towards the camera so far
};
#define AVSM_VOLUME_WALK_STATE MarchState
#include "common/volume.glsl"
#define AVSM_CACHE_SAMPLED
#include "common/volume_lighting_cache.glsl"

uint march_volume_count = 0u;
float march_step_voxels = 1.0;
bool march_skip_empty = true;
uint march_volume = 0u;  // the volume being walked (for its cache layout)

const float kMinTransmittance = 1e-3;

// One brick's stretch: the atlas offset is looked up once, then each step is two
// texture fetches. Same energy-conserving step as the reference march.
bool visit_volume_interval(GpuVolume volume, inout DensityReader reader, vec3 world_origin, vec3 world_direction,
                           vec3 index_origin, vec3 index_direction, float t_start, float t_end, inout MarchState state) {
  vec3 brick_offset;
  vec3 middle = index_origin + 0.5 * (t_start + t_end) * index_direction;
  if (!atlas_brick_offset(volume, volume_brick_of(volume, middle), brick_offset)) return true;
  GpuCacheLayout cache = cache_layouts[march_volume];
  float step_length = march_step_voxels * volume.voxel_size;
  int steps = max(1, int(ceil((t_end - t_start) / step_length)));
  float dt = (t_end - t_start) / float(steps);
  for (int i = 0; i < steps; ++i) {
    vec3 p = index_origin + (t_start + (float(i) + 0.5) * dt) * index_direction;
    float sigma_t = volume.extinction_scale * atlas_density(volume, p, brick_offset);
    if (sigma_t <= 0.0) continue;
    float step_transmittance = exp(-sigma_t * dt);
    state.in_scattered += state.transmittance * volume.albedo * (1.0 - step_transmittance) * cached_in_scattering(cache, p);
    state.transmittance *= step_transmittance;
    if (state.transmittance < kMinTransmittance) return false;
  }
  return true;
}

// Continues `state` along the world ray over [t_min, t_max] through every volume,
// front to back. `touched`: whether that stretch met any volume.
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
