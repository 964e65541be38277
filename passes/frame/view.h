#pragma once
// The camera of a frame, as the passes need it.
#include <glm/glm.hpp>

#include <cstdint>

#include "scene/camera.h"

namespace avsm::passes {

// What sizes the camera's targets: the setting a message names when one does not fit
// the device (gpu/device_limits.h).
inline constexpr const char* kCameraSizeSetting = "the image size (--width/--height, the viewer's window)";

struct View {
  glm::mat4 view{1.0f};
  glm::mat4 projection{1.0f};       // Vulkan clip space (depth 0..1), +y up with a flipped viewport
  glm::mat4 view_projection{1.0f};
  glm::mat4 inverse_view_projection{1.0f};
  glm::vec3 camera_position{0.0f};
  uint32_t width = 1, height = 1;
  float near_plane = 0.1f, far_plane = 100.0f;
};

View make_view(const scene::Camera& camera, uint32_t width, uint32_t height);

struct Ray {
  glm::vec3 origin, direction;  // direction unit length
};
// The camera ray through a pixel's centre, from the near plane: `pixel` x right, y down
// from the top-left corner, in pixels (row 0 at the top, as the renderer draws it).
Ray pixel_ray(const View& view, glm::vec2 pixel);

}  // namespace avsm::passes
