// The fog passes' camera rays (passes/camera/fog/): from the camera through a point of the
// image, in pixels (a centre at +0.5).
#ifndef AVSM_PASS_FOG_RAYS_GLSL
#define AVSM_PASS_FOG_RAYS_GLSL
#extension GL_GOOGLE_include_directive : require
#include "common/camera_rays.glsl"

vec3 fog_ray_direction(vec2 pixel) {
  vec3 far_point = unproject_pixel(pc.inverse_view_projection, pixel, pc.output_size, 1.0);
  return normalize(far_point - fog_grid.camera_sky.xyz);
}

// Distance from the camera to the depth buffer's surface at `pixel`, the background (depth
// 1) at the fog's far end.
float fog_surface_distance(vec2 pixel, float depth) {
  if (depth >= 1.0) return fog_far_distance();
  vec3 surface = unproject_pixel(pc.inverse_view_projection, pixel, pc.output_size, depth);
  return min(length(surface - fog_grid.camera_sky.xyz), fog_far_distance());
}

#endif
