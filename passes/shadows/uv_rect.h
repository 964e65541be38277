#pragma once
// A rectangle of a shadow map's uv square (0..1 on each side): what a caster covers
// seen from the light (light_footprint()), or what a page of a paged map covers.
#include <glm/glm.hpp>

namespace avsm::passes {

struct UvRect {
  glm::vec2 min{1.0f}, max{0.0f};  // empty until set

  static UvRect whole() { return {glm::vec2(0.0f), glm::vec2(1.0f)}; }
  bool empty() const { return !(min.x <= max.x && min.y <= max.y); }
  bool overlaps(const UvRect& other) const {
    return !empty() && !other.empty() && min.x <= other.max.x && other.min.x <= max.x && min.y <= other.max.y &&
           other.min.y <= max.y;
  }
  void extend(const UvRect& other) {
    if (other.empty()) return;
    min = empty() ? other.min : glm::min(min, other.min);
    max = empty() ? other.max : glm::max(max, other.max);
  }
};

}  // namespace avsm::passes
