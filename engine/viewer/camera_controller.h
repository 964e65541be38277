#pragma once
// Turns mouse and keyboard input into a scene camera. Two modes:
//  - orbit: left drag turns the camera around its target, right (or middle) drag
//    pans both, the wheel moves towards / away from the target;
//  - fly: right drag looks around (the target moves), W/A/S/D/Q/E move.
// Until the first input the camera is exactly the one it started from, so an
// untouched viewer renders what avsm-capture renders for that scene camera.
#include <glm/glm.hpp>

#include "scene/camera.h"

namespace avsm::viewer {

enum class CameraMode { orbit, fly };

// One frame's input, in pixels and seconds.
struct CameraInput {
  glm::vec2 mouse_delta{0.0f};
  bool rotate = false;     // left button held (orbit)
  bool pan_or_look = false;  // right or middle button held
  float scroll = 0.0f;     // wheel steps, positive away from the user (zoom in)
  glm::vec3 move{0.0f};    // fly: x right, y up, z forward, each -1..1
  bool fast = false;       // shift: move 4x faster
  float seconds = 0.0f;    // since the last frame
  float viewport_height = 1.0f;
};

class CameraController {
 public:
  explicit CameraController(const scene::Camera& start) { reset(start); }
  void reset(const scene::Camera& start);

  // Applies the input; returns true when the camera changed.
  bool update(const CameraInput& input);

  const scene::Camera& camera() const { return camera_; }
  // Turns the camera about its target around its up axis (a scripted orbit: the control
  // command "orbit DEGREES", as avsm-capture --orbit turns it).
  void turn_about_target(float radians) { camera_ = scene::orbited(camera_, radians); }
  CameraMode mode = CameraMode::orbit;
  // World units per second when flying; starts at a tenth of the start distance.
  float fly_speed = 1.0f;

 private:
  void orbit(glm::vec2 pixels);
  void pan(glm::vec2 pixels, float viewport_height);
  void zoom(float steps);
  void look(glm::vec2 pixels);
  void fly(const glm::vec3& move, float seconds);

  scene::Camera camera_;
};

}  // namespace avsm::viewer
