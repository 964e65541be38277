// The fast camera march, front part (passes/camera/volumes/volume_cached_march_pass.h): one thread per
// pixel of the march image, 1/divisor of the output resolution per axis. Each thread
// marches its ray up to the nearest opaque distance among the output pixels of its
// block and their neighbours one pixel around, so that every output pixel the upsample
// (volume_upsample.comp) blends it into lies at or behind where it stopped; the
// upsample marches the rest of each output pixel's ray itself. Writes in-scattering
// and transmittance, and the distance marched.
#ifndef AVSM_PASS_VOLUME_CACHED_MARCH_GLSL
#define AVSM_PASS_VOLUME_CACHED_MARCH_GLSL
#extension GL_GOOGLE_include_directive : require

#define AVSM_VOLUME_BINDING_NANOVDB 3
#define AVSM_VOLUME_BINDING_MAJORANTS 4
#define AVSM_VOLUME_BINDING_PARAMETERS 5
#define AVSM_VOLUME_BINDING_ATLAS 6
#define AVSM_CACHE_BINDING 8
#define AVSM_MARCH_LIGHTS_BINDING 10
#define AVSM_SHADOW_BINDING 11
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 15  // with lookups: the smoke asks for the pages it reads
#include "common/volume_cached_march.glsl"
#include "common/camera_rays.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D depth_texture;
layout(binding = 1, rgba16f) uniform writeonly image2D scattering_image;  // rgb in-scattered, a transmittance
layout(binding = 2, r32f) uniform writeonly image2D distance_image;       // camera distance marched to

#include "shared/passes/camera/volumes/volume_cached_march.h"


void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.march_size))) return;

  // The nearest opaque distance over the block grown by one output pixel.
  int window = int(pc.divisor) + 2;
  ivec2 corner = pixel * int(pc.divisor) - 1;
  float t_stop = 3.4e38;
  for (int i = 0; i < 36; ++i) {  // constant bound (lavapipe): divisor <= 4
    if (i >= window * window) break;
    ivec2 p = clamp(corner + ivec2(i % window, i / window), ivec2(0), ivec2(pc.output_size) - 1);
    vec3 surface = unproject_pixel(pc.inverse_view_projection, vec2(p) + 0.5, pc.output_size,
                                   texelFetch(depth_texture, p, 0).r);
    t_stop = min(t_stop, length(surface - pc.camera_position));
  }
  // This march pixel's own ray, through the centre of its block.
  vec3 through = unproject_pixel(pc.inverse_view_projection, (vec2(pixel) + 0.5) * float(pc.divisor), pc.output_size,
                                 1.0);
  vec3 direction = normalize(through - pc.camera_position);
  imageStore(distance_image, pixel, vec4(t_stop));
  MarchState state = MarchState(1.0, vec3(0.0));
  if (t_stop > 0.0) {
    march_volume_count = pc.volume_count;
    march_step_voxels = pc.step_voxels;
    march_light_count = pc.light_count;
    march_skip_empty = (pc.flags & kMarchNoMajorantSkipping) == 0u;
    bool touched;
    state = march_ray(pc.camera_position, direction, t_stop, touched);
  }
  imageStore(scattering_image, pixel, vec4(state.in_scattered, state.transmittance));
}

#endif
