// The reference camera march (--volume-shading reference): full resolution, steps of
// GpuVolume::step_length (a quarter voxel), NanoVDB density, and every light's
// shadow map looked up along the ray. What the fast path (volume_cached_march.glsl)
// is measured against.
//
// Before including, define the volume bindings (common/volume.glsl), AVSM_SHADOW_BINDING
// (common/shadow_lookup.glsl) and AVSM_MARCH_LIGHTS_BINDING (one GpuLight per light).
// Set march_volume_count, march_light_count and march_skip_empty before marching.
#ifndef AVSM_VOLUME_REFERENCE_MARCH_GLSL
#define AVSM_VOLUME_REFERENCE_MARCH_GLSL

#extension GL_GOOGLE_include_directive : require

#include "common/volume_march.glsl"
#include "common/lights.glsl"
#include "common/shadow_lookup.glsl"

layout(std430, binding = AVSM_MARCH_LIGHTS_BINDING) readonly buffer Lights { GpuLight lights[]; };
#include "common/scattered_light.glsl"

uint march_light_count = 0u;


// How many march steps share one in-scattering evaluation: one per shadow-map texel
// along the ray. Finer sampling cannot see more of the maps, and a filtered map
// lookup costs as much as many density samples.
int lighting_stride(vec3 p, float dt) {
  float spacing = 3.4e38;
  for (uint i = 0u; i < march_light_count; ++i) {
    GpuShadow s = shadows[i];
    if (s.technique != kShadowNone) spacing = min(spacing, shadow_texel_size(s, shadow_light_depth(s, p)));
  }
  return spacing >= 3.4e38 ? 1 : clamp(int(spacing / dt), 1, 64);
}

// Midpoint rule over [t_start, t_end] of the world ray, in steps of at most step_length.
// Each step attenuates by exp(-sigma_t dt) and adds the light scattered in it with the
// energy-conserving form T * albedo * (1 - exp(-sigma_t dt)) * L_in (the exact integral
// for constant sigma and L_in over the step), so bright, dense steps cannot add more
// light than they block.
void march_segment(GpuVolume volume, inout DensityReader reader, vec3 world_origin, vec3 world_direction,
                   vec3 index_origin, vec3 index_direction, float t_start, float t_end,
                   inout MarchState state) {
  int steps = max(1, int(ceil((t_end - t_start) / volume.step_length)));
  float dt = (t_end - t_start) / float(steps);
  bool scatters = (march_light_count > 0u || volume.sky_light > 0.0) && any(greaterThan(volume.albedo, vec3(0.0)));
  int stride = scatters ? lighting_stride(world_origin + t_start * world_direction, dt) : steps;
  // Blocks of `stride` steps share one in-scattering evaluation at their middle. The
  // inner loop only gathers the block's weight (sum of T * albedo * (1 - exp(-sigma dt)));
  // keeping the map lookups out of it keeps the hot density loop small (on lavapipe a
  // lookup inside it slowed every sample, looked up or not, about fourfold).
  for (int block_start = 0; block_start < steps; block_start += stride) {
    int block_end = min(block_start + stride, steps);
    vec3 weight = vec3(0.0);
    for (int i = block_start; i < block_end; ++i) {
      float t = t_start + (float(i) + 0.5) * dt;
      float sigma_t = volume.extinction_scale * sample_density(reader, index_origin + t * index_direction);
      if (sigma_t <= 0.0) continue;
      float step_transmittance = exp(-sigma_t * dt);
      weight += state.transmittance * volume.albedo * (1.0 - step_transmittance);
      state.transmittance *= step_transmittance;
      if (state.transmittance < kMinTransmittance) break;
    }
    if (scatters && any(greaterThan(weight, vec3(0.0)))) {
      float t_light = t_start + 0.5 * float(block_start + block_end) * dt;
      state.in_scattered += weight * scattered_light(march_volume, index_origin + t_light * index_direction,
                                                     world_origin + t_light * world_direction, -world_direction,
                                                     march_light_count);
    }
    if (state.transmittance < kMinTransmittance) return;
  }
}

// The brick walk calls this for each non-empty stretch of the ray.
bool visit_volume_interval(GpuVolume volume, inout DensityReader reader, vec3 world_origin, vec3 world_direction,
                           vec3 index_origin, vec3 index_direction, float t_start, float t_end, inout MarchState state) {
  march_segment(volume, reader, world_origin, world_direction, index_origin, index_direction, t_start, t_end, state);
  return state.transmittance >= kMinTransmittance;
}

#endif
