#pragma once
// The viewer window's layout: the panel docked in a column on the left, full height,
// and the 3D view beside it, which takes the rest of the window. The scene renders at
// the view's size (its own aspect), the blit copies it into the view's rectangle
// unscaled, and the mouse moves the camera and picks only over the view.
//
// The panel is kPanelWidth window units wide (ImGui's units; framebuffer pixels times
// the HiDPI scale), but never more than kPanelMaxPercent of the window's width: the
// view always keeps at least 60% of the width and the whole height. At 1280x720 the
// panel is 420 px and the view 860x720; at 960x540 384 px and 576x540; at 320x180
// 128 px and 192x180; at 160x90 64 px and 96x90.
//
// Pure arithmetic, no window or GPU: tests/viewer/viewer_logic_test.cpp covers it.
#include <glm/glm.hpp>

#include <cstdint>

namespace avsm::viewer {

// The panel's width in window units, when the window is wide enough.
constexpr float kPanelWidth = 420.0f;
// The most of the window's width the panel takes, in percent (rounded down to a pixel).
constexpr uint32_t kPanelMaxPercent = 40;

// A rectangle of framebuffer pixels: x right, y down from the window's top-left corner.
struct PixelRect {
  uint32_t x = 0, y = 0, width = 0, height = 0;
  bool empty() const { return width == 0 || height == 0; }
  // Whether framebuffer pixel `pixel` (whole numbers: a pixel's index) lies inside.
  bool contains(glm::vec2 pixel) const;
  bool operator==(const PixelRect&) const = default;
};

struct ViewLayout {
  glm::uvec2 framebuffer{0};  // the window in pixels (the swapchain's extent)
  glm::vec2 scale{1.0f};      // framebuffer pixels per window unit (2 on a HiDPI screen)
  PixelRect panel;            // the panel's column, at the left edge
  PixelRect view;             // the 3D view: right of the panel, the rest of the window

  // The panel's ImGui window, in window units (ImGui's coordinates).
  glm::vec2 panel_position() const;
  glm::vec2 panel_size() const;
  // A window position (ImGui's mouse position, in window units) as the pixel of the
  // view's image under it: x right, y down from the view's top-left pixel, whole
  // numbers (a pixel's index: picking casts the ray through its centre). Outside the
  // view it lies outside 0..view.width-1 / 0..view.height-1.
  glm::vec2 view_pixel(glm::vec2 window_position) const;
  // Whether a window position lies over the view (not the panel, not outside the window).
  bool in_view(glm::vec2 window_position) const;
};

// The layout of a window whose framebuffer is `framebuffer` pixels, `scale` pixels per
// window unit. A zero-sized (minimised) framebuffer gives empty rectangles.
ViewLayout layout_for(glm::uvec2 framebuffer, glm::vec2 scale = glm::vec2(1.0f));

}  // namespace avsm::viewer
