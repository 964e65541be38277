#include "viewer/view_layout.h"

#include <algorithm>
#include <cmath>

namespace avsm::viewer {

bool PixelRect::contains(glm::vec2 pixel) const {
  return pixel.x >= float(x) && pixel.y >= float(y) && pixel.x < float(x) + float(width) &&
         pixel.y < float(y) + float(height);
}

glm::vec2 ViewLayout::panel_position() const { return glm::vec2(panel.x, panel.y) / scale; }
glm::vec2 ViewLayout::panel_size() const { return glm::vec2(panel.width, panel.height) / scale; }

glm::vec2 ViewLayout::view_pixel(glm::vec2 window_position) const {
  // The framebuffer pixel under the position (its index), then relative to the view.
  return glm::floor(window_position * scale) - glm::vec2(view.x, view.y);
}

bool ViewLayout::in_view(glm::vec2 window_position) const {
  const glm::vec2 pixel = view_pixel(window_position);
  return pixel.x >= 0.0f && pixel.y >= 0.0f && pixel.x < float(view.width) && pixel.y < float(view.height);
}

ViewLayout layout_for(glm::uvec2 framebuffer, glm::vec2 scale) {
  ViewLayout layout;
  layout.framebuffer = framebuffer;
  layout.scale = glm::vec2(scale.x > 0.0f ? scale.x : 1.0f, scale.y > 0.0f ? scale.y : 1.0f);
  const uint32_t wanted = uint32_t(std::lround(kPanelWidth * layout.scale.x));
  const uint32_t most = uint32_t(uint64_t(framebuffer.x) * kPanelMaxPercent / 100);
  const uint32_t panel_width = std::min(wanted, most);
  layout.panel = {0, 0, panel_width, framebuffer.y};
  layout.view = {panel_width, 0, framebuffer.x - panel_width, framebuffer.y};
  return layout;
}

}  // namespace avsm::viewer
