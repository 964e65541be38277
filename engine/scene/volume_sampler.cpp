// CPU reference sampling of a Volume through NanoVDB, the same data structure
// the GPU reads, so differences point at the GPU code rather than at the data.
#include "scene/volume.h"

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include <algorithm>
#include <cmath>

namespace avsm::scene {
namespace {

const nanovdb::NanoGrid<float>* nano_grid(const Volume& volume) {
  if (volume.nanovdb.empty()) return nullptr;
  return reinterpret_cast<const nanovdb::NanoGrid<float>*>(volume.nanovdb.data());
}

glm::vec3 to_index(const Volume& volume, const glm::vec3& world) {
  return glm::vec3(volume.index_from_world * glm::vec4(world, 1.0f));
}

// Clips the index-space segment a + t (b - a), t in [0, 1], to the box where
// the density can be non-zero. Returns false if it misses.
bool clip_to_support(const Volume& volume, const glm::vec3& a, const glm::vec3& b, float& t0, float& t1) {
  const glm::vec3 lo = glm::vec3(volume.active_index_min - 1);
  const glm::vec3 hi = glm::vec3(volume.active_index_max + 1);
  t0 = 0.0f;
  t1 = 1.0f;
  for (int axis = 0; axis < 3; ++axis) {
    const float d = b[axis] - a[axis];
    if (std::abs(d) < 1e-12f) {
      if (a[axis] < lo[axis] || a[axis] > hi[axis]) return false;
      continue;
    }
    float near = (lo[axis] - a[axis]) / d, far = (hi[axis] - a[axis]) / d;
    if (near > far) std::swap(near, far);
    t0 = std::max(t0, near);
    t1 = std::min(t1, far);
  }
  return t0 < t1;
}

bool in_empty_brick(const MajorantGrid& majorant, const glm::vec3& index) {
  const glm::ivec3 brick = glm::ivec3(glm::floor((index - glm::vec3(majorant.index_origin)) / float(majorant.brick_size)));
  if (glm::any(glm::lessThan(brick, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(brick, majorant.dims))) return true;
  return majorant.at(brick) == 0.0f;
}

}  // namespace

float sample_density(const Volume& volume, const glm::vec3& world) {
  const auto* grid = nano_grid(volume);
  if (grid == nullptr) return 0.0f;
  const glm::vec3 index = to_index(volume, world);
  const auto accessor = grid->getAccessor();  // the sampler keeps a reference to it
  const auto sampler = nanovdb::createSampler<1>(accessor);
  return sampler(nanovdb::Vec3f(index.x, index.y, index.z));
}

float optical_depth(const Volume& volume, const glm::vec3& from, const glm::vec3& to, float step) {
  const auto* grid = nano_grid(volume);
  const float length = glm::length(to - from);
  if (grid == nullptr || !(length > 0.0f)) return 0.0f;
  const glm::vec3 a = to_index(volume, from), b = to_index(volume, to);
  float t0, t1;
  if (!clip_to_support(volume, a, b, t0, t1)) return 0.0f;

  if (!(step > 0.0f)) step = 0.25f * volume.smallest_voxel_edge();
  constexpr double kMaxSteps = 1 << 24;  // bounds the work for absurd inputs
  const auto steps = static_cast<std::uint32_t>(std::clamp(std::ceil(double(length) * (t1 - t0) / step), 1.0, kMaxSteps));
  const float dt = (t1 - t0) / float(steps);
  const auto accessor = grid->getAccessor();  // the sampler keeps a reference to it
  const auto sampler = nanovdb::createSampler<1>(accessor);
  double sum = 0.0;
  for (std::uint32_t i = 0; i < steps; ++i) {
    const glm::vec3 p = glm::mix(a, b, t0 + (float(i) + 0.5f) * dt);
    if (in_empty_brick(volume.majorant, p)) continue;
    sum += std::max(0.0f, sampler(nanovdb::Vec3f(p.x, p.y, p.z)));
  }
  return float(double(volume.extinction_scale) * sum * double(length) * double(dt));
}

float transmittance(const Volume& volume, const glm::vec3& from, const glm::vec3& to, float step) {
  return std::exp(-optical_depth(volume, from, to, step));
}

}  // namespace avsm::scene
