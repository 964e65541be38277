#include "viewer/camera_controller.h"

#include <algorithm>
#include <cmath>
#include <glm/gtc/matrix_transform.hpp>

namespace avsm::viewer {

namespace {

constexpr float kRadiansPerPixel = 0.005f;
constexpr float kZoomPerStep = 0.9f;         // distance factor per wheel step
constexpr float kMinPolarAngle = 0.02f;      // radians kept between the view direction and +/-up
constexpr float kMinDistance = 1e-3f;

glm::vec3 rotate(const glm::vec3& v, float radians, const glm::vec3& axis) {
  return glm::vec3(glm::rotate(glm::mat4(1.0f), radians, axis) * glm::vec4(v, 0.0f));
}

// Turns `direction` by yaw about `up` and pitch about the camera's right axis,
// stopping short of the poles so the view never flips over.
glm::vec3 turn(const glm::vec3& direction, const glm::vec3& up, float yaw, float pitch) {
  glm::vec3 d = rotate(direction, yaw, up);
  const glm::vec3 right = glm::normalize(glm::cross(d, up));
  const float length = glm::length(d);
  const float polar = std::acos(std::clamp(glm::dot(d / length, up), -1.0f, 1.0f));  // 0 = along +up
  const float wanted = std::clamp(polar - pitch, kMinPolarAngle, float(M_PI) - kMinPolarAngle);
  return rotate(d, polar - wanted, right);
}

}  // namespace

void CameraController::reset(const scene::Camera& start) {
  camera_ = start;
  fly_speed = std::max(glm::length(start.target - start.position) * 0.1f, 0.01f);
}

bool CameraController::update(const CameraInput& input) {
  const scene::Camera before = camera_;
  const bool dragged = input.mouse_delta != glm::vec2(0.0f);
  if (mode == CameraMode::orbit) {
    if (input.rotate && dragged) orbit(input.mouse_delta);
    else if (input.pan_or_look && dragged) pan(input.mouse_delta, input.viewport_height);
    if (input.scroll != 0.0f) zoom(input.scroll);
  } else {
    if (input.pan_or_look && dragged) look(input.mouse_delta);
    if (input.move != glm::vec3(0.0f)) fly(input.move * (input.fast ? 4.0f : 1.0f), input.seconds);
    if (input.scroll != 0.0f) fly_speed *= std::pow(1.0f / kZoomPerStep, input.scroll);
  }
  return camera_.position != before.position || camera_.target != before.target;
}

void CameraController::orbit(glm::vec2 pixels) {
  const glm::vec3 up = glm::normalize(camera_.up);
  // The scene turns with the mouse: dragging right moves the camera left around the
  // target, dragging down lifts it above.
  const glm::vec3 offset = turn(camera_.position - camera_.target, up, -pixels.x * kRadiansPerPixel,
                                pixels.y * kRadiansPerPixel);
  camera_.position = camera_.target + offset;
}

void CameraController::pan(glm::vec2 pixels, float viewport_height) {
  const glm::vec3 forward = camera_.target - camera_.position;
  const float distance = glm::length(forward);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera_.up));
  const glm::vec3 up = glm::normalize(glm::cross(right, forward));
  // One pixel is this many world units at the target's distance: the point under the cursor stays under it.
  const float units_per_pixel = 2.0f * distance * std::tan(camera_.vertical_fov * 0.5f) / std::max(viewport_height, 1.0f);
  const glm::vec3 shift = (-pixels.x * right + pixels.y * up) * units_per_pixel;
  camera_.position += shift;
  camera_.target += shift;
}

void CameraController::zoom(float steps) {
  const glm::vec3 offset = camera_.position - camera_.target;
  const float distance = std::max(glm::length(offset) * std::pow(kZoomPerStep, steps), kMinDistance);
  camera_.position = camera_.target + glm::normalize(offset) * distance;
}

void CameraController::look(glm::vec2 pixels) {
  const glm::vec3 up = glm::normalize(camera_.up);
  // The view follows the mouse: right looks right, down looks down.
  camera_.target = camera_.position + turn(camera_.target - camera_.position, up, -pixels.x * kRadiansPerPixel,
                                           -pixels.y * kRadiansPerPixel);
}

void CameraController::fly(const glm::vec3& move, float seconds) {
  const glm::vec3 forward = glm::normalize(camera_.target - camera_.position);
  const glm::vec3 right = glm::normalize(glm::cross(forward, camera_.up));
  const glm::vec3 up = glm::normalize(camera_.up);
  const glm::vec3 shift = (move.x * right + move.y * up + move.z * forward) * fly_speed * seconds;
  camera_.position += shift;
  camera_.target += shift;
}

}  // namespace avsm::viewer
