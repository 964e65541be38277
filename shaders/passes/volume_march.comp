#version 460
// Camera ray march through every fog volume, composited onto the lit opaque colour:
//   color = color * T_camera + in-scattered light.
// One thread per pixel. The ray ends at the opaque surface in the depth buffer.
// Volumes are marched front to back by their entry distance along this pixel's
// ray; transmittance carries from one to the next. Inside a volume the ray walks
// the majorant bricks (3D DDA); empty bricks are skipped, and the others are
// sampled at the midpoints of equal steps of at most GpuVolume::step_length.
#extension GL_GOOGLE_include_directive : require

struct MarchState {
  float transmittance;  // camera to the current point
  vec3 in_scattered;    // radiance scattered towards the camera so far
};
#define AVSM_VOLUME_WALK_STATE MarchState
#define AVSM_VOLUME_BINDING_NANOVDB 2
#define AVSM_VOLUME_BINDING_MAJORANTS 3
#define AVSM_VOLUME_BINDING_PARAMETERS 4
#include "common/volume.glsl"
#include "common/lights.glsl"
#define AVSM_SHADOW_BINDING 6
#include "common/shadow_lookup.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba16f) uniform image2D color_image;
layout(binding = 1) uniform sampler2D depth_texture;
layout(std430, binding = 5) readonly buffer Lights { GpuLight lights[]; };

// Mirrors VolumePass::Push (passes/volume_pass.cpp).
layout(push_constant) uniform Push {
  mat4 inverse_view_projection;
  vec3 camera_position;
  uint volume_count;
  uvec2 image_size;
  uint light_count;
  uint flags;
} pc;

const uint kFlagNoMajorantSkipping = 1u;  // debug: march empty bricks too (results must not change)
// Below this the rest of the ray cannot change the pixel visibly (it would add
// at most 1e-3 of the remaining light), so the march stops.
const float kMinTransmittance = 1e-3;


// World position of a pixel at a depth-buffer value. Vulkan depth 0..1, and the
// viewport is flipped so that +y is up: pixel row 0 is the top of the image.
vec3 unproject(ivec2 pixel, float depth) {
  vec2 ndc = vec2(2.0 * (float(pixel.x) + 0.5) / float(pc.image_size.x) - 1.0,
                  1.0 - 2.0 * (float(pixel.y) + 0.5) / float(pc.image_size.y));
  vec4 world = pc.inverse_view_projection * vec4(ndc, depth, 1.0);
  return world.xyz / world.w;
}

// Light arriving at world point p from every light, towards the camera, per unit sigma_s.
vec3 incoming_light(vec3 p, vec3 to_camera) {
  vec3 sum = vec3(0.0);
  for (uint i = 0u; i < pc.light_count; ++i) {
    vec3 to_light;
    vec3 radiance = light_radiance(lights[i], p, to_light);
    sum += radiance * phase_function(to_camera, to_light) * light_transmittance(i, p);
  }
  return sum;
}

// How many march steps share one in-scattering evaluation: one per shadow-map texel
// along the ray. Finer sampling cannot see more of the maps, and a filtered map
// lookup costs as much as many density samples.
int lighting_stride(vec3 p, float dt) {
  float spacing = 3.4e38;
  for (uint i = 0u; i < pc.light_count; ++i) {
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
  bool scatters = pc.light_count > 0u && any(greaterThan(volume.albedo, vec3(0.0)));
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
      state.in_scattered += weight * incoming_light(world_origin + t_light * world_direction, -world_direction);
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

void march_volume(uint v, vec3 world_origin, vec3 world_direction, float t_enter, float t_exit,
                  inout MarchState state) {
  walk_volume_bricks(v, world_origin, world_direction, t_enter, t_exit, (pc.flags & kFlagNoMajorantSkipping) == 0u,
                     state);
}

// The volume hit next after (previous_enter, previous_index) in (entry distance, index)
// order: a selection step instead of a sort, so there is no per-thread array and no
// limit on the volume count (volumes are few).
bool next_volume(vec3 world_origin, vec3 world_direction, float t_max, float previous_enter, int previous_index,
                 out uint next, out float next_enter, out float next_exit) {
  bool found = false;
  next_enter = 3.4e38;
  for (uint v = 0u; v < pc.volume_count; ++v) {
    float t_enter, t_exit;
    if (!volume_interval(v, world_origin, world_direction, t_max, t_enter, t_exit)) continue;
    bool after_previous = t_enter > previous_enter || (t_enter == previous_enter && int(v) > previous_index);
    if (after_previous && t_enter < next_enter) {
      found = true;
      next = v;
      next_enter = t_enter;
      next_exit = t_exit;
    }
  }
  return found;
}

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.image_size))) return;

  vec3 surface = unproject(pixel, texelFetch(depth_texture, pixel, 0).r);
  vec3 origin = pc.camera_position;
  float t_max = length(surface - origin);
  if (!(t_max > 0.0)) return;
  vec3 direction = (surface - origin) / t_max;

  MarchState state = MarchState(1.0, vec3(0.0));
  bool touched = false;
  float previous_enter = -1.0;
  int previous_index = -1;
  uint v;
  float t_enter, t_exit;
  while (state.transmittance >= kMinTransmittance &&
         next_volume(origin, direction, t_max, previous_enter, previous_index, v, t_enter, t_exit)) {
    march_volume(v, origin, direction, t_enter, t_exit, state);
    touched = true;
    previous_enter = t_enter;
    previous_index = int(v);
  }
  // Pixels whose ray meets no volume keep their colour bit for bit.
  if (!touched) return;
  vec4 color = imageLoad(color_image, pixel);
  imageStore(color_image, pixel, vec4(color.rgb * state.transmittance + state.in_scattered, color.a));
}
