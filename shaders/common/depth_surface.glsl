// The opaque surfaces a depth buffer holds, for passes that work per camera pixel:
// their points and normals. Before including, declare the depth buffer as a sampler2D
// and #define DEPTH_SURFACE_TEXTURE to its name.
#ifndef AVSM_DEPTH_SURFACE_GLSL
#define AVSM_DEPTH_SURFACE_GLSL
#ifndef DEPTH_SURFACE_TEXTURE
#error depth_surface.glsl: #define DEPTH_SURFACE_TEXTURE to the depth buffer's sampler2D before including it
#endif
#include "common/camera_rays.glsl"

// The camera the depth buffer was rendered through.
struct DepthCamera {
  mat4 inverse_view_projection;
  uvec2 image_size;
};

// Depth-buffer value of the far plane: no surface.
const float kFarDepth = 1.0;

vec3 depth_pixel_point(DepthCamera camera, ivec2 pixel, float depth) {
  return unproject_pixel(camera.inverse_view_projection, vec2(pixel) + 0.5, camera.image_size, depth);
}

// The surface point of a pixel, if it has one (inside the image, nearer than far).
bool depth_surface_point(DepthCamera camera, ivec2 pixel, out vec3 p) {
  p = vec3(0.0);
  if (any(lessThan(pixel, ivec2(0))) || any(greaterThanEqual(uvec2(pixel), camera.image_size))) return false;
  float depth = texelFetch(DEPTH_SURFACE_TEXTURE, pixel, 0).r;
  if (depth >= kFarDepth) return false;
  p = depth_pixel_point(camera, pixel, depth);
  return true;
}

// The world step of one pixel along an image axis from p (the surface at `pixel`):
// towards the neighbour closer to p, so that the step stays on p's own surface at
// depth edges.
bool depth_surface_step(DepthCamera camera, ivec2 pixel, vec3 p, ivec2 axis, out vec3 step) {
  vec3 a, b;
  bool has_a = depth_surface_point(camera, pixel + axis, a);
  bool has_b = depth_surface_point(camera, pixel - axis, b);
  step = vec3(0.0);
  if (has_a && (!has_b || distance(a, p) <= distance(b, p))) {
    step = a - p;
    return true;
  }
  if (has_b) {
    step = p - b;
    return true;
  }
  return false;
}

// The surface normal at `pixel` (point p) from the neighbouring depth texels, facing the
// camera; `to_camera` where the neighbours do not span a plane.
vec3 depth_surface_normal(DepthCamera camera, ivec2 pixel, vec3 p, vec3 to_camera) {
  vec3 dx, dy;
  if (!depth_surface_step(camera, pixel, p, ivec2(1, 0), dx) || !depth_surface_step(camera, pixel, p, ivec2(0, 1), dy))
    return to_camera;
  vec3 n = cross(dx, dy);
  float len = length(n);
  if (!(len > 1e-20)) return to_camera;
  n /= len;
  return dot(n, to_camera) < 0.0 ? -n : n;
}
#endif
