#include "passes/frame/view.h"

#include <glm/gtc/matrix_transform.hpp>

namespace avsm::passes {

View make_view(const scene::Camera& camera, uint32_t width, uint32_t height) {
  View v;
  v.width = width;
  v.height = height;
  v.near_plane = camera.near_plane;
  v.far_plane = camera.far_plane;
  v.camera_position = camera.position;
  v.view = glm::lookAt(camera.position, camera.target, camera.up);
  v.projection = glm::perspectiveRH_ZO(camera.vertical_fov, float(width) / float(height), camera.near_plane,
                                       camera.far_plane);
  v.view_projection = v.projection * v.view;
  v.inverse_view_projection = glm::inverse(v.view_projection);
  return v;
}

Ray pixel_ray(const View& view, glm::vec2 pixel) {
  // Clip y is +1 at the top row (the renderer flips the viewport).
  const glm::vec2 ndc((pixel.x + 0.5f) / float(view.width) * 2.0f - 1.0f,
                      1.0f - (pixel.y + 0.5f) / float(view.height) * 2.0f);
  auto unproject = [&](float z) {
    const glm::vec4 p = view.inverse_view_projection * glm::vec4(ndc, z, 1.0f);
    return glm::vec3(p) / p.w;
  };
  const glm::vec3 near_point = unproject(0.0f), far_point = unproject(1.0f);
  return {near_point, glm::normalize(far_point - near_point)};
}

}  // namespace avsm::passes
