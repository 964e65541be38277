// Camera rays of the passes that work per pixel.
#ifndef AVSM_CAMERA_RAYS_GLSL
#define AVSM_CAMERA_RAYS_GLSL

// World position at a point of an image of `image_size` pixels and a depth-buffer
// value. Vulkan depth 0..1, and the viewport is flipped so that +y is up: row 0 is
// the top of the image. `position` is in pixels (a pixel centre is at +0.5).
vec3 unproject_pixel(mat4 inverse_view_projection, vec2 position, uvec2 image_size, float depth) {
  vec2 ndc = vec2(2.0 * position.x / float(image_size.x) - 1.0, 1.0 - 2.0 * position.y / float(image_size.y));
  vec4 world = inverse_view_projection * vec4(ndc, depth, 1.0);
  return world.xyz / world.w;
}

#endif
