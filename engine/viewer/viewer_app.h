#pragma once
// avsm-viewer: a window on a LiveRenderer. Each loop iteration polls the watched
// files (hot reload), takes input (camera, clicks, keys) and the panel's edits,
// renders a scene frame only when something changed (lavapipe frames are slow),
// blits the tonemapped image into the 3D view, draws the panel in its column beside
// it and presents. The panel is docked at the left, the view takes the rest of the
// window and the scene renders at the view's size (view_layout.h).
// Frames in flight (`frames_in_flight`, renderer/frame_slots.h): scene frames and window
// frames each take turns in their own slots (command buffer, fence, executor; the window's
// also its acquire semaphore and panel buffers); a scene frame's results (timings,
// overflow, texel curves) are read when its fence signals, not after its submit.
//
// Scripted runs (tests and CI, where no one clicks): `frames` renders that many
// scene frames and exits; `screenshot_dir` then receives what avsm-capture writes
// for one frame (frame.png: the view) plus window.png (the window as presented, panel
// included) and layout.json (where the panel and the view lie in it), and
// `inspect_pixel` clicks a pixel of the view first and writes inspect.json there as well.
// `control` takes commands on stdin instead (engine/viewer/control_commands.h).
#include <glm/glm.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>

#include "scene/volume.h"

namespace avsm::viewer {

#ifndef AVSM_DEFAULT_SCENE
#define AVSM_DEFAULT_SCENE "content/default/scene.json"
#endif

struct ViewerOptions {
  std::filesystem::path scene = AVSM_DEFAULT_SCENE;
  uint32_t width = 1280, height = 720;  // window size
  bool validation = false;
  std::string device;                    // see gpu::ContextDesc::device
  std::filesystem::path out_dir = "out/viewer";  // where the screenshot key writes (shot-001, ...)
  scene::VolumeShadingOverrides volume_shading;  // over the scene's volume_shading
  // Scripted mode.
  uint32_t frames = 0;                   // > 0: render this many scene frames, then exit
  std::filesystem::path screenshot_dir;  // after the last scripted frame
  std::optional<glm::vec2> inspect_pixel;  // clicked before the first frame; a pixel of the view (frame.png)
  // Driven by commands on stdin instead (control_commands.h); replies on stdout.
  bool control = false;
  // Scene and window frames the CPU may record ahead of the GPU (1..passes::kMaxFramesInFlight).
  uint32_t frames_in_flight = 2;
};

// Runs until the window closes (or the scripted frames are done). Returns the exit
// code: 0, or 1 after printing why (validation messages, a failed scripted step).
// Throws WindowError when no window can be opened, and the LiveRenderer's errors
// when the scene cannot be loaded at all.
int run_viewer(const ViewerOptions& options);

}  // namespace avsm::viewer
