#pragma once
#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <string>

namespace avsm::scene {

struct Camera {
  std::string name;
  glm::vec3 position{0.0f, 0.0f, 5.0f};
  glm::vec3 target{0.0f};
  glm::vec3 up{0.0f, 1.0f, 0.0f};
  float vertical_fov = 0.785398f;  // radians
  float near_plane = 0.1f;
  float far_plane = 100.0f;
};

// The camera turned `radians` about its target, around its up axis (a turntable: what
// the viewer's orbit does, and what `avsm-capture --orbit` does each frame).
inline Camera orbited(const Camera& camera, float radians) {
  Camera turned = camera;
  turned.position = camera.target + glm::angleAxis(radians, glm::normalize(camera.up)) * (camera.position - camera.target);
  return turned;
}

}  // namespace avsm::scene
