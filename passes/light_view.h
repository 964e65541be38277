#pragma once
// How a shadowed light sees the scene: the projection its transmittance map is
// rendered with, and the light-space depth every capture, resolve and lookup
// uses. Depth is distance along the light's axis (from the light for a spot, from
// a plane in front of the casters for a directional light), linear in world
// units, so segments, nodes and receivers compare directly.
#include <glm/glm.hpp>

#include <cstdint>

#include "scene/bounds.h"
#include "scene/light.h"

namespace avsm::passes {

struct LightView {
  glm::mat4 light_from_world{1.0f};  // world -> light clip space (Vulkan, z 0..1); map uv = clip.xy / w * 0.5 + 0.5
  glm::mat4 world_from_light{1.0f};  // its inverse, for per-texel rays
  glm::vec4 depth_plane{0.0f};       // depth(p) = dot(xyz, p) + w
  glm::vec3 eye{0.0f};               // the spot light, or the centre of the directional light's near face
  bool perspective = false;          // spot light
  float near_depth = 0.0f;           // depth range the casters lie in
  float far_depth = 1.0f;
  // World size of one level-0 texel at depth d: texel_size_base + texel_size_per_depth * d.
  float texel_size_base = 0.0f;
  float texel_size_per_depth = 0.0f;
  uint32_t resolution = 1;

  float depth(const glm::vec3& p) const { return glm::dot(glm::vec3(depth_plane), p) + depth_plane.w; }
  float texel_size(float d) const { return texel_size_base + texel_size_per_depth * d; }
};

// Fits the light's frustum around `casters` (the scene bounds: everything that
// casts or receives). A directional light gets an orthographic box around the
// bounding sphere; a spot light a perspective frustum of its outer cone, from a
// near plane just in front of the casters to the farthest corner.
LightView make_light_view(const scene::Light& light, const scene::Bounds& casters, uint32_t resolution);

// The point hair ribbons turn to face in the light's captures: the spot light itself,
// or for a directional light a point far back along its direction (so ribbons face
// along it).
glm::vec3 hair_ribbon_facing_point(const LightView& light);

}  // namespace avsm::passes
