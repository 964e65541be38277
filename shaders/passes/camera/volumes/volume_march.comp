#version 460
// The reference camera march (passes/camera/volumes/volume_pass.h): one thread per pixel, composited
// onto the lit opaque colour in place: color = color * T_camera + in-scattered light.
// The ray ends at the opaque surface in the depth buffer. With fog, the colour is already
// fogged (fog_apply.comp) and the smoke goes over it at its distance (smoke_over_fogged). Volumes are marched front
// to back by their entry distance along this pixel's ray; transmittance carries from
// one to the next. Inside a volume the ray walks the majorant bricks (3D DDA); empty
// bricks are skipped, and the others are sampled at the midpoints of equal steps of
// at most GpuVolume::step_length (common/volume_reference_march.glsl).
#extension GL_GOOGLE_include_directive : require

#define AVSM_VOLUME_BINDING_NANOVDB 2
#define AVSM_VOLUME_BINDING_MAJORANTS 3
#define AVSM_VOLUME_BINDING_PARAMETERS 4
#define AVSM_MARCH_LIGHTS_BINDING 5
#define AVSM_SHADOW_BINDING 6
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 10  // the smoke asks for the pages it reads
#include "common/volume_reference_march.glsl"
#include "common/camera_rays.glsl"
#define AVSM_FOG_BINDING 11
#define AVSM_FOG_INTEGRATED_BINDING 12
#include "common/fog.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba16f) uniform image2D color_image;
layout(binding = 1) uniform sampler2D depth_texture;

#include "shared/passes/camera/volumes/volume_march.h"


void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.image_size))) return;

  vec3 surface = unproject_pixel(pc.inverse_view_projection, vec2(pixel) + 0.5, pc.image_size,
                                 texelFetch(depth_texture, pixel, 0).r);
  vec3 origin = pc.camera_position;
  float t_max = length(surface - origin);
  if (!(t_max > 0.0)) return;
  vec3 direction = (surface - origin) / t_max;

  march_volume_count = pc.volume_count;
  march_light_count = pc.light_count;
  march_skip_empty = (pc.flags & kMarchNoMajorantSkipping) == 0u;
  bool touched;
  MarchState state = march_ray(origin, direction, t_max, touched);
  // Pixels whose ray meets no volume keep their colour bit for bit.
  if (!touched) return;
  vec4 color = imageLoad(color_image, pixel);
  vec3 composite = color.rgb * state.transmittance + state.in_scattered;
  if (fog_grid.enabled != 0u)
    composite = smoke_over_fogged(color.rgb, vec4(state.in_scattered, state.transmittance), vec2(pixel) + 0.5,
                                  smoke_fog_distance(pc.volume_count, origin, direction, t_max));
  imageStore(color_image, pixel, vec4(composite, color.a));
}
