#pragma once
// avsm-viewer --control: the viewer driven by commands on stdin, one per line, for
// tests and tools that have no input devices (under Xvfb nobody clicks). After each
// command the viewer prints one JSON line on stdout. Commands:
//   frame                    poll the watched files, render a scene frame, present; the
//                            reply also counts the validation messages so far, gives
//                            the view's size ("view": [W, H], the frame's) and the pages
//                            paged maps' receivers asked for and did not find ("pages_pending")
//   inspect X,Y              click pixel (X, Y) of the view (x right, y down; a pixel of
//                            the frame, not the window): plot its texel curves
//   screenshot DIR           write one avsm-capture frame's outputs, window.png and layout.json
//   light I FIELD VALUE      set a panel field of light I: technique (avsm, ...), nodes,
//                            resolution, filter (point, ...), sort (on/off), build (lists,
//                            fixed), fit (view, scene), cascades (1-4), clusters (0-8, 0 and
//                            1 off), layout (dense, paged), kernel (none, box, gaussian),
//                            on (on/off), position X,Y,Z (spot, point), direction
//                            X,Y,Z (directional, spot; normalised)
//   exposure V               the tonemapper's exposure
//   orbit DEGREES            turn the camera about its target (as a drag does; the next
//                            frame shows it)
//   levels I|off             tint light I's receivers by the shadow map level they read
//                            (the panel's "shadow levels" overlay), or stop
//   time SECONDS             move the timeline's playhead there (the scene's animation,
//                            snapped to the timeline's frames); the reply has the time
//   play, pause              play the animation, one timeline frame per 'frame', or stop
//   quit                     stop (the exit status still reports validation messages)
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "viewer/scene_overrides.h"

namespace avsm::viewer {

struct ControlCommand {
  enum class Kind { frame, inspect, screenshot, light, exposure, orbit, levels, time, quit };
  Kind kind = Kind::frame;
  glm::vec2 pixel{0.0f};             // inspect
  std::filesystem::path directory;   // screenshot
  uint32_t light = 0;                // light
  std::string field, value;          // light
  float exposure = 1.0f;             // exposure
  float degrees = 0.0f;              // orbit
  std::optional<uint32_t> overlay_light;  // levels (nullopt: off)
  float seconds = 0.0f;                   // time
  std::optional<bool> play;               // play (true), pause (false); unset: time scrubs
};

// Throws std::invalid_argument saying what is wrong with the line.
ControlCommand parse_control_command(const std::string& line);

// Sets light `light`'s `field` to `value` in the overrides (the panel's fields, by
// name). Throws std::invalid_argument for an unknown field or a bad value.
void set_light_field(SceneOverrides& overrides, uint32_t light, const std::string& field, const std::string& value);

}  // namespace avsm::viewer
