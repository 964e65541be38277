// Finishes the fast camera march at full resolution and composites it onto the colour:
// color = color * T + in-scattered (passes/camera/volumes/volume_upsample_pass.h). The march image
// (volume_cached_march.comp) holds each ray's front part, up to a distance no output
// pixel it serves lies in front of. Where the four march pixels around this pixel
// stopped at about the same distance they are blended bilinearly; at a depth edge the
// one that stopped nearest is taken alone (its front part is in front of this pixel's
// surface too), so smoke neither halos over an opaque silhouette nor leaks behind one.
// Then this pixel's own ray is marched from there to its own opaque surface: the
// stretch that decides how much smoke lies in front of a surface inside the smoke.
#ifndef AVSM_PASS_VOLUME_UPSAMPLE_GLSL
#define AVSM_PASS_VOLUME_UPSAMPLE_GLSL
#extension GL_GOOGLE_include_directive : require

#define AVSM_VOLUME_BINDING_NANOVDB 4
#define AVSM_VOLUME_BINDING_MAJORANTS 5
#define AVSM_VOLUME_BINDING_PARAMETERS 6
#define AVSM_VOLUME_BINDING_ATLAS 7
#define AVSM_CACHE_BINDING 9
#define AVSM_MARCH_LIGHTS_BINDING 11
#define AVSM_SHADOW_BINDING 12
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 16  // with lookups: the smoke asks for the pages it reads
#include "common/volume_cached_march.glsl"
#include "common/camera_rays.glsl"
#define AVSM_FOG_BINDING 17
#define AVSM_FOG_INTEGRATED_BINDING 18
#include "common/fog.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba16f) uniform image2D color_image;
layout(binding = 1) uniform sampler2D depth_texture;
layout(binding = 2) uniform sampler2D scattering_texture;
layout(binding = 3) uniform sampler2D distance_texture;

#include "shared/passes/camera/volumes/volume_upsample.h"

// Relative spread of the march pixels' stop distances below which they are blended.
const float kSameSurface = 0.05;

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.output_size))) return;
  vec3 surface = unproject_pixel(pc.inverse_view_projection, vec2(pixel) + 0.5, pc.output_size,
                                 texelFetch(depth_texture, pixel, 0).r);
  float t_surface = length(surface - pc.camera_position);
  if (!(t_surface > 0.0)) return;
  vec3 direction = (surface - pc.camera_position) / t_surface;

  // March pixel m covers output pixels [m * divisor, (m + 1) * divisor).
  vec2 position = (vec2(pixel) + 0.5) / float(pc.divisor) - 0.5;
  ivec2 base = ivec2(floor(position));
  vec2 f = position - vec2(base);
  vec4 blended = vec4(0.0), nearest = vec4(0.0, 0.0, 0.0, 1.0);
  float blended_stop = 0.0, nearest_stop = 3.4e38, farthest_stop = 0.0;
  for (int tap = 0; tap < 4; ++tap) {
    ivec2 offset = ivec2(tap & 1, tap >> 1);
    ivec2 m = clamp(base + offset, ivec2(0), ivec2(pc.march_size) - 1);
    vec4 value = texelFetch(scattering_texture, m, 0);
    float stop = texelFetch(distance_texture, m, 0).r;
    vec2 w = mix(1.0 - f, f, vec2(offset));
    blended += w.x * w.y * value;
    blended_stop += w.x * w.y * stop;
    farthest_stop = max(farthest_stop, stop);
    if (stop < nearest_stop) {
      nearest_stop = stop;
      nearest = value;
    }
  }
  bool same_surface = farthest_stop - nearest_stop < kSameSurface * nearest_stop;
  vec4 front = same_surface ? blended : nearest;
  float t_front = min(same_surface ? blended_stop : nearest_stop, t_surface);

  march_volume_count = pc.volume_count;
  march_step_voxels = pc.step_voxels;
  march_light_count = pc.light_count;
  march_skip_empty = (pc.flags & kMarchNoMajorantSkipping) == 0u;
  bool touched;
  MarchState state = march_ray_between(pc.camera_position, direction, t_front, t_surface,
                                       MarchState(front.a, front.rgb), touched);
  // Where no smoke is, the colour keeps its bits.
  if (state.transmittance == 1.0 && all(equal(state.in_scattered, vec3(0.0)))) return;
  vec4 color = imageLoad(color_image, pixel);
  vec3 composite = color.rgb * state.transmittance + state.in_scattered;
  // With fog the colour is already fogged (fog_apply.comp); the smoke goes over it at its distance.
  if (fog_grid.enabled != 0u)
    composite = smoke_over_fogged(color.rgb, vec4(state.in_scattered, state.transmittance), vec2(pixel) + 0.5,
                                  smoke_fog_distance(pc.volume_count, pc.camera_position, direction, t_surface));
  imageStore(color_image, pixel, vec4(composite, color.a));
}

#endif
