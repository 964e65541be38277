#include "passes/shadows/shadow_clusters.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <utility>

#include "scene/scene.h"

namespace avsm::passes {
namespace {

// An object's extent in the light's plane: x, y of the light-space box.
struct Extent {
  glm::vec2 min{std::numeric_limits<float>::infinity()}, max{-std::numeric_limits<float>::infinity()};
  void extend(const Extent& o) {
    min = glm::min(min, o.min);
    max = glm::max(max, o.max);
  }
  float size() const { return std::max(max.x - min.x, max.y - min.y); }
};

Extent light_extent(const scene::Light& light, const scene::Bounds& box) {
  const glm::vec3 direction = glm::normalize(light.direction);
  const glm::vec3 up = std::abs(direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
  const bool spot = light.type == scene::LightType::spot;
  const glm::vec3 eye = spot ? light.position : glm::vec3(0.0f);
  const glm::mat4 view = glm::lookAtRH(eye, eye + direction, up);
  Extent e;
  for (int corner = 0; corner < 8; ++corner) {
    const glm::vec3 p((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                      (corner & 4) ? box.max.z : box.min.z);
    const glm::vec3 q = glm::vec3(view * glm::vec4(p, 1.0f));
    // A spot light's plane is its view-plane tangents; corners at or behind the light
    // spread to the whole cone.
    const glm::vec2 xy = spot ? (-q.z > 1e-3f ? glm::vec2(q) / -q.z : glm::vec2(q) * 1e3f) : glm::vec2(q);
    e.min = glm::min(e.min, xy);
    e.max = glm::max(e.max, xy);
  }
  return e;
}

// Seed 004, eq. 2: how far apart two extents' corners are.
float distance(const Extent& a, const Extent& b) {
  const glm::vec2 lo = glm::abs(a.min - b.min), hi = glm::abs(a.max - b.max);
  return std::max({lo.x, lo.y, hi.x, hi.y});
}

}  // namespace

std::vector<uint32_t> mesh_caster_objects(const scene::Scene& scene) {
  std::vector<uint32_t> objects;
  uint32_t draw = 0;  // OpaquePass draws only meshes with triangles; they come first among the objects
  for (const scene::Mesh& mesh : scene.meshes) objects.push_back(mesh.indices.empty() ? kNoCasterObject : draw++);
  return objects;
}

std::vector<CasterObject> scene_caster_objects(const scene::Scene& scene) {
  std::vector<CasterObject> objects;
  const std::vector<uint32_t> mesh_objects = mesh_caster_objects(scene);
  for (size_t m = 0; m < scene.meshes.size(); ++m)
    if (mesh_objects[m] != kNoCasterObject)
      objects.push_back({CasterObject::Kind::mesh_draw, mesh_objects[m], 1, scene.meshes[m].bounds, scene.meshes[m].name});
  uint32_t segment = 0;
  for (const scene::HairGroom& groom : scene.hair) {
    uint32_t segments = 0;
    for (size_t s = 0; s < groom.strand_count(); ++s)
      segments += std::max<uint32_t>(groom.strand_offsets[s + 1] - groom.strand_offsets[s], 1) - 1;
    if (segments > 0) objects.push_back({CasterObject::Kind::strands, segment, segments, groom.bounds, groom.name});
    segment += segments;
  }
  for (uint32_t v = 0; v < scene.volumes.size(); ++v)
    objects.push_back({CasterObject::Kind::volume, v, 1, scene.volumes[v].world_bounds, scene.volumes[v].name});
  return objects;
}

std::vector<CasterCluster> cluster_casters(const scene::Light& light, const std::vector<CasterObject>& objects,
                                           uint32_t max_clusters) {
  std::vector<Extent> extents(objects.size());  // by object
  std::vector<std::vector<uint32_t>> clusters;   // object indices; one object each to start
  uint32_t volumes = 0;
  for (uint32_t i = 0; i < objects.size(); ++i) {
    if (objects[i].kind == CasterObject::Kind::volume) ++volumes;
    if (objects[i].bounds.empty()) continue;
    extents[i] = light_extent(light, objects[i].bounds);
    clusters.push_back({i});
  }
  if (volumes > kMaxClusteredVolumes || max_clusters < 2 || clusters.size() < 2) return {};
  auto object_extent = [&](uint32_t object) { return extents[object]; };
  // Complete linkage: two clusters are as far apart as their farthest two objects.
  auto linkage = [&](const std::vector<uint32_t>& a, const std::vector<uint32_t>& b) {
    float d = 0.0f;
    for (uint32_t i : a)
      for (uint32_t j : b) d = std::max(d, distance(object_extent(i), object_extent(j)));
    return d;
  };
  auto cluster_extent = [&](const std::vector<uint32_t>& c) {
    Extent e;
    for (uint32_t i : c) e.extend(object_extent(i));
    return e;
  };
  while (clusters.size() > 1) {
    size_t best_a = 0, best_b = 1;
    float best = std::numeric_limits<float>::infinity();
    for (size_t a = 0; a < clusters.size(); ++a)
      for (size_t b = a + 1; b < clusters.size(); ++b) {
        const float d = linkage(clusters[a], clusters[b]);
        if (d < best) best = d, best_a = a, best_b = b;
      }
    const float threshold =
        0.25f * std::min(cluster_extent(clusters[best_a]).size(), cluster_extent(clusters[best_b]).size());
    if (clusters.size() <= max_clusters && best > threshold) break;
    clusters[best_a].insert(clusters[best_a].end(), clusters[best_b].begin(), clusters[best_b].end());
    clusters.erase(clusters.begin() + std::ptrdiff_t(best_b));
  }
  // A cluster's grooms must be one range of segments (StrandCasters has one): a cluster
  // that holds grooms on both sides of another's takes that one's cluster in.
  auto strands_span = [&](const std::vector<uint32_t>& c) {
    uint32_t lo = ~0u, hi = 0;
    for (uint32_t i : c)
      if (objects[i].kind == CasterObject::Kind::strands) lo = std::min(lo, i), hi = std::max(hi, i);
    return std::pair(lo, hi);
  };
  for (bool merged = true; merged;) {
    merged = false;
    for (size_t a = 0; a < clusters.size() && !merged; ++a) {
      const auto [lo, hi] = strands_span(clusters[a]);
      for (size_t b = 0; b < clusters.size() && !merged; ++b) {
        if (b == a) continue;
        for (uint32_t i : clusters[b])
          if (objects[i].kind == CasterObject::Kind::strands && i > lo && i < hi) merged = true;
        if (merged) {
          clusters[a].insert(clusters[a].end(), clusters[b].begin(), clusters[b].end());
          clusters.erase(clusters.begin() + std::ptrdiff_t(b));
        }
      }
    }
  }
  if (clusters.size() < 2) return {};
  std::vector<CasterCluster> out;
  for (std::vector<uint32_t>& c : clusters) {
    CasterCluster cluster;
    std::sort(c.begin(), c.end());
    for (uint32_t i : c) cluster.bounds.extend(objects[i].bounds);
    cluster.objects = std::move(c);
    out.push_back(std::move(cluster));
  }
  return out;
}

}  // namespace avsm::passes
