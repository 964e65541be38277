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

}  // namespace avsm::passes
