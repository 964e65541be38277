#version 460
// The fog over the opaque colour, reference (--volume-shading reference): each pixel's ray
// marched from the camera to its surface (or the fog's far end) in pc.reference_steps equal
// steps, the medium and every light's transmittance looked up at each step's middle. The
// fast path (fog_apply.comp) is measured against it. The steps are split over dispatches
// (pc.first_step, pc.dispatch_steps), the fog so far kept in fog_state between them: lavapipe
// ends a shader's loops after 65535 iterations in all, and an area light's every virtual
// light at every step would pass that.
#extension GL_GOOGLE_include_directive : require

#define AVSM_SHADOW_BINDING 3
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 8
#include "common/lights.glsl"
#include "common/shadow_lookup.glsl"
layout(std430, binding = 7) readonly buffer Lights { GpuLight lights[]; };
#define AVSM_FOG_BINDING 2
#define AVSM_FOG_LIGHTING
#include "common/fog.glsl"
#include "shared/passes/camera/fog/fog.h"
#include "passes/camera/fog/fog_rays.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba16f) uniform image2D color_image;
layout(binding = 1) uniform sampler2D depth_texture;
layout(binding = 9, rgba32f) uniform image2D fog_state;  // rgb in-scattered, a transmittance so far

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.output_size))) return;
  vec2 centre = vec2(pixel) + 0.5;
  float distance = fog_surface_distance(centre, texelFetch(depth_texture, pixel, 0).r);
  vec3 direction = fog_ray_direction(centre);
  float step_length = distance / float(pc.reference_steps);
  vec4 fog = pc.first_step == 0u ? vec4(0.0, 0.0, 0.0, 1.0) : imageLoad(fog_state, pixel);
  uint end = min(pc.first_step + pc.dispatch_steps, pc.reference_steps);
  for (uint k = 0u; k < 4096u; ++k) {  // constant bound, break on the count (lavapipe)
    uint s = pc.first_step + k;
    if (s >= end) break;
    vec3 p = fog_grid.camera_sky.xyz + (float(s) + 0.5) * step_length * direction;
    FogMediumSample medium = fog_medium_at(p);
    fog = fog_then(fog, fog_slice(fog_in_scattering(p, direction, medium, pc.light_count), medium.extinction, step_length));
  }
  if (end < pc.reference_steps) {
    imageStore(fog_state, pixel, fog);
    return;
  }
  vec4 color = imageLoad(color_image, pixel);
  imageStore(color_image, pixel, vec4(color.rgb * fog.a + fog.rgb, color.a));
}
