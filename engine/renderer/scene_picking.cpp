#include "renderer/scene_picking.h"

#include <algorithm>
#include <cmath>
#include <limits>

namespace avsm::renderer {

namespace {

constexpr float kNoHit = std::numeric_limits<float>::infinity();

// Moeller-Trumbore; both faces count (the frame draws double-sided materials too).
float triangle_hit(const Ray& ray, const glm::vec3& a, const glm::vec3& b, const glm::vec3& c) {
  const glm::vec3 ab = b - a, ac = c - a;
  const glm::vec3 p = glm::cross(ray.direction, ac);
  const float det = glm::dot(ab, p);
  if (std::abs(det) < 1e-12f) return kNoHit;
  const float inverse = 1.0f / det;
  const glm::vec3 s = ray.origin - a;
  const float u = glm::dot(s, p) * inverse;
  if (u < 0.0f || u > 1.0f) return kNoHit;
  const glm::vec3 q = glm::cross(s, ab);
  const float v = glm::dot(ray.direction, q) * inverse;
  if (v < 0.0f || u + v > 1.0f) return kNoHit;
  const float t = glm::dot(ac, q) * inverse;
  return t > 0.0f ? t : kNoHit;
}

struct MeshHit {
  float t = kNoHit;
  glm::vec3 normal{0.0f};
};

MeshHit mesh_hit(const Ray& ray, const scene::Mesh& mesh, float nearest) {
  const auto [enter, leave] = scene::ray_span(mesh.bounds, ray.origin, ray.direction);
  if (enter > leave || enter >= nearest) return {};
  MeshHit best;
  for (size_t i = 0; i + 2 < mesh.indices.size(); i += 3) {
    const glm::vec3 &a = mesh.positions[mesh.indices[i]], &b = mesh.positions[mesh.indices[i + 1]],
                    &c = mesh.positions[mesh.indices[i + 2]];
    const float t = triangle_hit(ray, a, b, c);
    if (t < best.t) best = {t, glm::cross(b - a, c - a)};
  }
  if (best.t < kNoHit) {
    best.normal = glm::normalize(best.normal);
    if (glm::dot(best.normal, ray.direction) > 0.0f) best.normal = -best.normal;  // the side the camera sees
  }
  return best;
}

}  // namespace

std::optional<PickedPoint> pick_point(const scene::Scene& scene, const passes::View& view, glm::vec2 pixel) {
  const Ray ray = pixel_ray(view, pixel);
  MeshHit nearest;
  const scene::Mesh* hit_mesh = nullptr;
  for (const scene::Mesh& mesh : scene.meshes) {
    const MeshHit hit = mesh_hit(ray, mesh, nearest.t);
    if (hit.t < nearest.t) nearest = hit, hit_mesh = &mesh;
  }
  if (hit_mesh) return PickedPoint{ray.origin + nearest.t * ray.direction, "mesh '" + hit_mesh->name + "'", nearest.normal};

  for (const scene::Volume& volume : scene.volumes) {
    const auto [enter, leave] = scene::ray_span(volume.world_bounds, ray.origin, ray.direction);
    if (enter <= leave && leave < kNoHit)
      return PickedPoint{ray.origin + 0.5f * (enter + leave) * ray.direction, "volume '" + volume.name + "'"};
  }
  return std::nullopt;
}

}  // namespace avsm::renderer

