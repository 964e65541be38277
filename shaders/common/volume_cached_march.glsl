// The fast camera march: density from the brick atlas (one hardware-trilinear fetch
// per sample) and in-scattering from the lighting cache (one more), no shadow-map
// lookups along the ray, and steps of march_step_voxels voxels. Shared by the camera
// march (volume_cached_march.comp) and the hair's per-vertex fog (hair_lighting.comp).
//
// With AVSM_MARCH_MAP_LOOKUPS, a volume whose lighting cache is off (dims 0) looks
// every light's map up at each step instead, exact like the reference and as costly.
// Only then are the lookups compiled in: on lavapipe their mere presence made the
// cached march three times slower.
//
// Before including, define the volume bindings (common/volume.glsl, atlas included)
// and AVSM_CACHE_BINDING (common/volume_lighting_cache.glsl); with lookups also
// AVSM_SHADOW_BINDING (common/shadow_lookup.glsl) and AVSM_MARCH_LIGHTS_BINDING (one
// GpuLight per light). Set march_volume_count, march_light_count, march_step_voxels
// and march_skip_empty before marching.
#ifndef AVSM_VOLUME_CACHED_MARCH_GLSL
#define AVSM_VOLUME_CACHED_MARCH_GLSL

#extension GL_GOOGLE_include_directive : require

#include "common/volume_march.glsl"
#define AVSM_CACHE_SAMPLED
#include "common/volume_lighting_cache.glsl"
#ifdef AVSM_MARCH_MAP_LOOKUPS
#include "common/lights.glsl"
#include "common/shadow_lookup.glsl"

layout(std430, binding = AVSM_MARCH_LIGHTS_BINDING) readonly buffer Lights { GpuLight lights[]; };
#include "common/scattered_light.glsl"
#endif

uint march_light_count = 0u;
float march_step_voxels = 2.0;

// In a volume without lighting cache: every light's map looked up (only compiled in
// with AVSM_MARCH_MAP_LOOKUPS; the renderer never runs such a volume without it).
vec3 looked_up_in_scattering(vec3 index_position, vec3 p, vec3 to_camera) {
#ifdef AVSM_MARCH_MAP_LOOKUPS
  return scattered_light(march_volume, index_position, p, to_camera, march_light_count);
#else
  return vec3(0.0);
#endif
}

// One brick's stretch: the atlas offset is looked up once, then each step is two
// texture fetches. Same energy-conserving step as the reference march.
bool visit_volume_interval(GpuVolume volume, inout DensityReader reader, vec3 world_origin, vec3 world_direction,
                           vec3 index_origin, vec3 index_direction, float t_start, float t_end, inout MarchState state) {
  vec3 brick_offset;
  vec3 middle = index_origin + 0.5 * (t_start + t_end) * index_direction;
  if (!atlas_brick_offset(volume, volume_brick_of(volume, middle), brick_offset)) return true;
  GpuCacheLayout cache = cache_layouts[march_volume];
  bool cached = cache.dims.x > 0;
  float step_length = march_step_voxels * volume.voxel_size;
  int steps = max(1, int(ceil((t_end - t_start) / step_length)));
  float dt = (t_end - t_start) / float(steps);
  for (int i = 0; i < steps; ++i) {
    float t = t_start + (float(i) + 0.5) * dt;
    vec3 p = index_origin + t * index_direction;
    float sigma_t = volume.extinction_scale * atlas_density(volume, p, brick_offset);
    if (sigma_t <= 0.0) continue;
    float step_transmittance = exp(-sigma_t * dt);
    vec3 in_scattering = cached ? cached_in_scattering(cache, p)
                                : looked_up_in_scattering(p, world_origin + t * world_direction, -world_direction);
    state.in_scattered += state.transmittance * volume.albedo * (1.0 - step_transmittance) * in_scattering;
    state.transmittance *= step_transmittance;
    if (state.transmittance < kMinTransmittance) return false;
  }
  return true;
}

#endif
