// Smoke seen from a light (passes/capture_smoke_pass.h): one thread per light texel
// marches every fog volume along the texel's light ray (majorant bricks skipped, the
// reference camera march's step) and appends the ray's optical depth as segments, one
// per `samples_per_segment` samples and never across an empty brick, so each segment
// carries its exact transmittance exp(-tau). Empty bricks emit nothing. The density
// comes from the brick atlas where the includer defines AVSM_VOLUME_BINDING_ATLAS
// (capture_smoke.comp), else from NanoVDB (capture_smoke_nanovdb.comp: hosts that pass
// no atlas). Before including, define AVSM_CAPTURE_BINDING.
#ifndef AVSM_CAPTURE_SMOKE_GLSL
#define AVSM_CAPTURE_SMOKE_GLSL
#extension GL_GOOGLE_include_directive : require

struct SmokeRay {
  ivec2 texel;
  float depth_origin;  // light depth at t = 0
  float depth_per_t;   // light depth gained per world unit along the ray
};
#define AVSM_VOLUME_WALK_STATE SmokeRay
#define AVSM_VOLUME_BINDING_NANOVDB 0
#define AVSM_VOLUME_BINDING_MAJORANTS 1
#define AVSM_VOLUME_BINDING_PARAMETERS 2
#include "common/volume.glsl"
#define AVSM_CAPTURE_APPEND
#include "common/capture_lists.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

#include "shared/passes/capture_smoke.h"

// Below this a segment changes transmittance by less than 1e-5: not worth a node.
const float kMinOpticalDepth = 1e-5;

void emit(SmokeRay ray, float t0, float t1, float tau) {
  if (tau > kMinOpticalDepth)
    capture_append(ray.texel, ray.depth_origin + t0 * ray.depth_per_t, ray.depth_origin + t1 * ray.depth_per_t,
                   exp(-tau));
}

bool visit_volume_interval(GpuVolume volume, inout DensityReader reader, vec3 world_origin, vec3 world_direction,
                           vec3 index_origin, vec3 index_direction, float t_start, float t_end, inout SmokeRay ray) {
  int steps = max(1, int(ceil((t_end - t_start) / volume.step_length)));
  float dt = (t_end - t_start) / float(steps);
#ifdef AVSM_VOLUME_BINDING_ATLAS
  vec3 brick_offset;
  vec3 middle = index_origin + 0.5 * (t_start + t_end) * index_direction;
  if (!atlas_brick_offset(volume, volume_brick_of(volume, middle), brick_offset)) return true;
#endif
  int per_segment = int(max(pc.samples_per_segment, 1u));
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
      emit(ray, segment_start, segment_end, tau);
      segment_start = segment_end;
      tau = 0.0;
    }
  }
  return true;
}

vec3 unproject(vec2 ndc, float z) {
  vec4 p = pc.world_from_light * vec4(ndc, z, 1.0);
  return p.xyz / p.w;
}

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.resolution)))) return;
  vec2 ndc = (vec2(texel) + 0.5) / float(pc.resolution) * 2.0 - 1.0;
  vec3 origin = unproject(ndc, 0.0);
  vec3 far_point = unproject(ndc, 1.0);
  float t_max = length(far_point - origin);
  if (!(t_max > 0.0)) return;
  vec3 direction = (far_point - origin) / t_max;
  SmokeRay ray = SmokeRay(texel, dot(pc.depth_plane.xyz, origin) + pc.depth_plane.w, dot(pc.depth_plane.xyz, direction));
  for (uint v = 0u; v < pc.volume_count; ++v) {
    float t_enter, t_exit;
    if (volume_interval(v, origin, direction, t_max, t_enter, t_exit))
      walk_volume_bricks(v, origin, direction, t_enter, t_exit, true, ray);
  }
}

#endif
