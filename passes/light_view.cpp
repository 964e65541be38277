#include "passes/light_view.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace avsm::passes {
namespace {

glm::vec3 up_vector_for(const glm::vec3& direction) {
  return std::abs(direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
}

// The caster box, or a unit box at the origin when the scene is empty.
scene::Bounds usable_bounds(const scene::Bounds& casters) {
  if (!casters.empty()) return casters;
  scene::Bounds unit;
  unit.extend(glm::vec3(-1.0f));
  unit.extend(glm::vec3(1.0f));
  return unit;
}

LightView directional_view(const glm::vec3& direction, const scene::Bounds& casters) {
  const glm::vec3 center = casters.center();
  const float radius = std::max(0.5f * glm::length(casters.size()), 1e-3f);
  // The eye sits one radius in front of the sphere, so depths run [radius, 3 radius].
  const glm::vec3 eye = center - direction * (2.0f * radius);
  const glm::mat4 view = glm::lookAtRH(eye, center, up_vector_for(direction));
  const glm::mat4 projection = glm::orthoRH_ZO(-radius, radius, -radius, radius, radius, 3.0f * radius);
  LightView v;
  v.light_from_world = projection * view;
  v.depth_plane = glm::vec4(direction, -glm::dot(direction, eye));
  v.eye = eye;
  v.near_depth = radius;
  v.far_depth = 3.0f * radius;
  v.texel_size_base = 2.0f * radius;  // divided by the resolution below
  return v;
}

LightView spot_view(const scene::Light& light, const scene::Bounds& casters) {
  const glm::vec3 direction = glm::normalize(light.direction);
  float nearest = INFINITY, farthest = 0.0f;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? casters.max.x : casters.min.x, (corner & 2) ? casters.max.y : casters.min.y,
                      (corner & 4) ? casters.max.z : casters.min.z);
    const float d = glm::dot(p - light.position, direction);
    nearest = std::min(nearest, d);
    farthest = std::max(farthest, d);
  }
  const float far_depth = std::max(farthest, 1e-2f);
  // The box's nearest corner can be behind the light; the near plane then sits close
  // to it (a thousandth of the range keeps depth precision usable).
  const float near_depth = std::clamp(nearest * 0.95f, far_depth * 1e-3f, far_depth * 0.5f);
  const float half_angle = std::clamp(light.outer_cone_angle, 0.01f, glm::radians(85.0f));
  const glm::mat4 view = glm::lookAtRH(light.position, light.position + direction, up_vector_for(direction));
  const glm::mat4 projection = glm::perspectiveRH_ZO(2.0f * half_angle, 1.0f, near_depth, far_depth);
  LightView v;
  v.light_from_world = projection * view;
  v.depth_plane = glm::vec4(direction, -glm::dot(direction, light.position));
  v.eye = light.position;
  v.perspective = true;
  v.near_depth = near_depth;
  v.far_depth = far_depth;
  v.texel_size_per_depth = 2.0f * std::tan(half_angle);  // divided by the resolution below
  return v;
}

}  // namespace

LightView make_light_view(const scene::Light& light, const scene::Bounds& casters, uint32_t resolution) {
  const scene::Bounds box = usable_bounds(casters);
  LightView v = light.type == scene::LightType::spot ? spot_view(light, box)
                                                     : directional_view(glm::normalize(light.direction), box);
  v.world_from_light = glm::inverse(v.light_from_world);
  v.resolution = std::max(resolution, 1u);
  v.texel_size_base /= float(v.resolution);
  v.texel_size_per_depth /= float(v.resolution);
  return v;
}

glm::vec3 hair_ribbon_facing_point(const LightView& light) {
  if (light.perspective) return light.eye;
  return light.eye - glm::vec3(light.depth_plane) * (1e3f * light.far_depth);
}

}  // namespace avsm::passes
