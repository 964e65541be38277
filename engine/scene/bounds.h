#pragma once
// Axis-aligned bounding box; starts empty (min > max) so extend() just works.
#include <glm/glm.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

namespace avsm::scene {

struct Bounds {
  glm::vec3 min{std::numeric_limits<float>::infinity()};
  glm::vec3 max{-std::numeric_limits<float>::infinity()};

  bool empty() const { return !(min.x <= max.x && min.y <= max.y && min.z <= max.z); }
  glm::vec3 center() const { return 0.5f * (min + max); }
  glm::vec3 size() const { return empty() ? glm::vec3(0.0f) : max - min; }

  void extend(const glm::vec3& point) {
    min = glm::min(min, point);
    max = glm::max(max, point);
  }
  void extend(const Bounds& other) {
    if (other.empty()) return;
    extend(other.min);
    extend(other.max);
  }
  bool contains(const glm::vec3& point) const {
    return glm::all(glm::lessThanEqual(min, point)) && glm::all(glm::lessThanEqual(point, max));
  }
  bool contains(const Bounds& other) const { return other.empty() || (contains(other.min) && contains(other.max)); }
  // Corner i of 8: bit 0 picks max.x over min.x, bit 1 max.y, bit 2 max.z.
  glm::vec3 corner(int i) const {
    return {(i & 1) ? max.x : min.x, (i & 2) ? max.y : min.y, (i & 4) ? max.z : min.z};
  }
};

// Slab test: where the ray origin + t * direction, t >= 0, enters and leaves `box`
// (enter > leave: it misses). Axis-parallel rays need no special case: 1 / 0 is +-inf,
// and the NaN of a ray starting on a slab's plane is ignored.
inline std::pair<float, float> ray_span(const Bounds& box, const glm::vec3& origin, const glm::vec3& direction) {
  float enter = 0.0f, leave = std::numeric_limits<float>::infinity();
  for (int axis = 0; axis < 3; ++axis) {
    const float inverse = 1.0f / direction[axis];
    float t0 = (box.min[axis] - origin[axis]) * inverse;
    float t1 = (box.max[axis] - origin[axis]) * inverse;
    if (t0 > t1) std::swap(t0, t1);
    if (!std::isnan(t0)) enter = std::max(enter, t0);
    if (!std::isnan(t1)) leave = std::min(leave, t1);
  }
  return {enter, leave};
}

// The box around the eight transformed corners of `box`.
inline Bounds transform_bounds(const Bounds& box, const glm::mat4& transform) {
  Bounds result;
  if (box.empty()) return result;
  for (int corner = 0; corner < 8; ++corner) result.extend(glm::vec3(transform * glm::vec4(box.corner(corner), 1.0f)));
  return result;
}

}  // namespace avsm::scene
