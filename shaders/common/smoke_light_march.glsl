// Smoke seen from a light: one light texel's ray through every fog volume (majorant
// bricks skipped, the reference camera march's step), its optical depth cut into
// segments of `samples_per_segment` samples that never cross an empty brick, so each
// carries its exact transmittance exp(-tau). The capture appends them to lists
// (common/capture_smoke.glsl); the fixed-memory build inserts them into the texel's
// curve as the march goes (passes/shadows/techniques/avsm/avsm_fixed_build.comp).
//
// Before including, define the volume bindings (common/volume.glsl; with
// AVSM_VOLUME_BINDING_ATLAS the density comes from the brick atlas, else from NanoVDB)
// and declare
//   void smoke_light_segment(ivec2 texel, float entry_depth, float exit_depth, float transmittance);
// which gets each segment front to back within a volume.
#ifndef AVSM_SMOKE_LIGHT_MARCH_GLSL
#define AVSM_SMOKE_LIGHT_MARCH_GLSL
#extension GL_GOOGLE_include_directive : require

struct SmokeRay {
  ivec2 texel;
  float depth_origin;         // light depth at t = 0
  float depth_per_t;          // light depth gained per world unit along the ray
  uint samples_per_segment;
  float stop_depth;           // no segment starts at or behind it (an opaque blocker)
};
#define AVSM_VOLUME_WALK_STATE SmokeRay
#include "common/volume.glsl"

// Below this a segment changes transmittance by less than 1e-5: not worth a node.
const float kMinOpticalDepth = 1e-5;

bool visit_volume_interval(GpuVolume volume, inout DensityReader reader, vec3 world_origin, vec3 world_direction,
                           vec3 index_origin, vec3 index_direction, float t_start, float t_end, inout SmokeRay ray) {
  if (ray.depth_origin + t_start * ray.depth_per_t >= ray.stop_depth) return false;
  int steps = max(1, int(ceil((t_end - t_start) / volume.step_length)));
  float dt = (t_end - t_start) / float(steps);
#ifdef AVSM_VOLUME_BINDING_ATLAS
  vec3 brick_offset;
  vec3 middle = index_origin + 0.5 * (t_start + t_end) * index_direction;
  if (!atlas_brick_offset(volume, volume_brick_of(volume, middle), brick_offset)) return true;
#endif
  int per_segment = int(max(ray.samples_per_segment, 1u));
  float segment_start = t_start, tau = 0.0;
  for (int i = 0; i < steps; ++i) {
    float t = t_start + (float(i) + 0.5) * dt;
#ifdef AVSM_VOLUME_BINDING_ATLAS
    tau += volume.extinction_scale * atlas_density(volume, index_origin + t * index_direction, brick_offset) * dt;
#else
    tau += volume.extinction_scale * sample_density(reader, index_origin + t * index_direction) * dt;
#endif
    if ((i + 1) % per_segment == 0 || i + 1 == steps) {
      float segment_end = t_start + float(i + 1) * dt;
      if (tau > kMinOpticalDepth)
        smoke_light_segment(ray.texel, ray.depth_origin + segment_start * ray.depth_per_t,
                            ray.depth_origin + segment_end * ray.depth_per_t, exp(-tau));
      segment_start = segment_end;
      tau = 0.0;
    }
  }
  return true;
}

// Marches texel `texel` of a light map through volumes 0..volume_count-1 that
// `volume_mask` selects (bit v for volume v < 32; volumes from 32 on always march). The
// map is the window at `raster_origin` of a `raster_resolution`^2 raster (LightView:
// a page of a paged map; a dense map is its own raster at origin 0).
void march_smoke_from_light(ivec2 texel, uvec2 raster_origin, uint raster_resolution, mat4 world_from_light,
                            vec4 depth_plane, uint volume_count, uint volume_mask, uint samples_per_segment,
                            float stop_depth) {
  vec2 ndc = (vec2(uvec2(texel) + raster_origin) + 0.5) / float(raster_resolution) * 2.0 - 1.0;
  vec4 near_h = world_from_light * vec4(ndc, 0.0, 1.0), far_h = world_from_light * vec4(ndc, 1.0, 1.0);
  vec3 origin = near_h.xyz / near_h.w, far_point = far_h.xyz / far_h.w;
  float t_max = length(far_point - origin);
  if (!(t_max > 0.0)) return;
  vec3 direction = (far_point - origin) / t_max;
  SmokeRay ray = SmokeRay(texel, dot(depth_plane.xyz, origin) + depth_plane.w, dot(depth_plane.xyz, direction),
                          samples_per_segment, stop_depth);
  for (uint v = 0u; v < volume_count; ++v) {
    if (v < 32u && (volume_mask & (1u << v)) == 0u) continue;
    float t_enter, t_exit;
    if (volume_interval(v, origin, direction, t_max, t_enter, t_exit))
      walk_volume_bricks(v, origin, direction, t_enter, t_exit, true, ray);
  }
}

#endif
