#include "scene/volume_scattering.h"

#include <nanovdb/NanoVDB.h>
#include <nanovdb/util/SampleFromVoxels.h>

#include <algorithm>
#include <cmath>
#include <random>
#include <thread>
#include <utility>

namespace avsm::scene {
namespace {

constexpr float kPi = 3.14159265358979f;

// Extinction (sigma_t per world unit) at world points, through NanoVDB's own trilinear
// sampler (as scene::sample_density), with one accessor kept across samples.
class Extinction {
 public:
  explicit Extinction(const Volume& volume)
      : volume_(volume),
        grid_(reinterpret_cast<const nanovdb::NanoGrid<float>*>(volume.nanovdb.data())),
        accessor_(grid_->getAccessor()),
        sampler_(nanovdb::createSampler<1>(accessor_)) {}

  float at_index(const glm::vec3& index) {
    return volume_.extinction_scale * std::max(0.0f, sampler_(nanovdb::Vec3f(index.x, index.y, index.z)));
  }
  float at(const glm::vec3& world) { return at_index(glm::vec3(volume_.index_from_world * glm::vec4(world, 1.0f))); }
  float majorant() const { return volume_.max_extinction(); }

 private:
  const Volume& volume_;
  using Accessor = nanovdb::NanoGrid<float>::AccessorType;
  const nanovdb::NanoGrid<float>* grid_;
  Accessor accessor_;  // before the sampler, which keeps a reference to it
  decltype(nanovdb::createSampler<1>(std::declval<const Accessor&>())) sampler_;
};

glm::vec3 sphere_direction(int i, int count) {  // a Fibonacci spiral: even, deterministic
  const float z = 1.0f - (2.0f * float(i) + 1.0f) / float(count);
  const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
  const float phi = float(i) * kPi * (3.0f - std::sqrt(5.0f));
  return {r * std::cos(phi), r * std::sin(phi), z};
}

// Optical depth from index point `p` to the volume's edge along world direction `world_direction`,
// in steps of half a brick (sky light is soft), empty bricks skipped.
float optical_depth_to_edge(const Volume& volume, Extinction& extinction, const glm::vec3& p,
                            const glm::vec3& world_direction) {
  const glm::vec3 index_direction = glm::normalize(glm::mat3(volume.index_from_world) * world_direction);
  const float world_per_index = glm::length(glm::mat3(volume.world_from_index) * index_direction);
  const Bounds support{glm::vec3(volume.active_index_min - 1), glm::vec3(volume.active_index_max + 1)};
  const auto [enter, exit] = ray_span(support, p, index_direction);
  if (!(enter < exit)) return 0.0f;
  const MajorantGrid& m = volume.majorant;
  const float step = std::max(1.0f, 0.5f * float(m.brick_size));
  const int steps = int(std::ceil((exit - enter) / step));
  float depth = 0.0f;
  for (int i = 0; i < steps; ++i) {
    const float t = enter + (float(i) + 0.5f) * (exit - enter) / float(steps);
    const glm::vec3 q = p + t * index_direction;
    const glm::ivec3 brick = glm::ivec3(glm::floor((q - glm::vec3(m.index_origin)) / float(m.brick_size)));
    if (glm::any(glm::lessThan(brick, glm::ivec3(0))) || glm::any(glm::greaterThanEqual(brick, m.dims)) ||
        m.at(brick) == 0.0f)
      continue;
    depth += extinction.at_index(q);
  }
  return steps > 0 ? depth * (exit - enter) / float(steps) * world_per_index : 0.0f;
}

// Uniform random numbers in [0, 1) for one ray's paths.
class Random {
 public:
  explicit Random(std::uint32_t seed) : engine_(seed) {}
  float next() { return std::uniform_real_distribution<float>(0.0f, 1.0f)(engine_); }
  glm::vec3 direction() {  // uniform on the sphere
    const float z = 1.0f - 2.0f * next(), phi = 2.0f * kPi * next();
    const float r = std::sqrt(std::max(0.0f, 1.0f - z * z));
    return {r * std::cos(phi), r * std::sin(phi), z};
  }

 private:
  std::minstd_rand engine_;
};

// Ratio tracking: an unbiased estimate of the transmittance over [0, length] of the ray.
float ratio_tracked_transmittance(Extinction& extinction, Random& random, const glm::vec3& origin,
                                  const glm::vec3& direction, float length) {
  const float majorant = extinction.majorant();
  float transmittance = 1.0f, t = 0.0f;
  while (transmittance > 0.0f) {
    t -= std::log(1.0f - random.next()) / majorant;
    if (t >= length) break;
    transmittance *= std::max(0.0f, 1.0f - extinction.at(origin + t * direction) / majorant);
  }
  return transmittance;
}

// How far the ray from `p` runs inside the volume's world bounds.
float distance_to_edge(const Volume& volume, const glm::vec3& p, const glm::vec3& direction) {
  const auto [enter, exit] = ray_span(volume.world_bounds, p, direction);
  return enter < exit ? exit : 0.0f;
}

// One path: the radiance it brings back along the ray (origin outside or inside the volume).
glm::vec3 trace_path(const Volume& volume, Extinction& extinction, Random& random, std::span<const Light> lights,
                     const glm::vec3& sky, glm::vec3 x, glm::vec3 direction, int max_bounces) {
  const float majorant = extinction.majorant();
  constexpr float kIsotropicPhase = 1.0f / (4.0f * kPi);
  glm::vec3 radiance(0.0f), throughput(1.0f);
  for (int bounce = 0; bounce < max_bounces; ++bounce) {
    auto [t, exit] = ray_span(volume.world_bounds, x, direction);
    if (!(t < exit)) break;
    bool scattered = false;  // delta tracking to a real collision
    for (;;) {
      t -= std::log(1.0f - random.next()) / majorant;
      if (t >= exit) break;
      if (random.next() * majorant < extinction.at(x + t * direction)) {
        scattered = true;
        break;
      }
    }
    if (!scattered) break;  // left the volume: the sky was counted at every event
    x += t * direction;
    throughput *= volume.albedo;
    for (const Light& light : lights) {
      glm::vec3 to_light;
      const glm::vec3 incoming = light_radiance(light, x, to_light);
      if (incoming == glm::vec3(0.0f)) continue;
      float length = distance_to_edge(volume, x, to_light);
      if (light.type != LightType::directional) length = std::min(length, glm::length(light.position - x));
      radiance += throughput * incoming * kIsotropicPhase *
                  ratio_tracked_transmittance(extinction, random, x, to_light, length);
    }
    // The sky: one direction drawn with the phase function's own density (so phase / pdf = 1).
    const glm::vec3 towards_sky = random.direction();
    radiance += throughput * sky *
                ratio_tracked_transmittance(extinction, random, x, towards_sky, distance_to_edge(volume, x, towards_sky));
    direction = random.direction();  // isotropic scattering
    if (bounce >= 4) {  // Russian roulette once the path has dimmed
      const float keep = std::min(1.0f, std::max({throughput.r, throughput.g, throughput.b}));
      if (random.next() >= keep) break;
      throughput /= keep;
    }
  }
  return radiance;
}

}  // namespace

std::size_t sky_lighting_corners(const Volume& volume) {
  const glm::ivec3 corners = volume.majorant.dims + 1;
  return std::size_t(corners.x) * std::size_t(corners.y) * std::size_t(corners.z);
}

std::vector<float> sky_lighting(const Volume& volume) {
  const MajorantGrid& m = volume.majorant;
  const glm::ivec3 corners = m.dims + 1;
  const MultipleScattering& scattering = volume.multiple_scattering;
  const int octaves = std::clamp(scattering.octaves, 1, 8);
  std::vector<float> grid(sky_lighting_corners(volume) * 4, 1.0f);
  if (volume.nanovdb.empty()) return grid;
  // One slab of corners per thread: each corner is independent.
  auto fill_slabs = [&](int first, int stride) {
    Extinction extinction(volume);
    for (int z = first; z < corners.z; z += stride)
      for (int y = 0; y < corners.y; ++y)
        for (int x = 0; x < corners.x; ++x) {
          const glm::vec3 p = glm::vec3(m.index_origin + glm::ivec3(x, y, z) * m.brick_size);
          float visibility[8] = {};
          for (int d = 0; d < kSkyDirections; ++d) {
            const float depth = optical_depth_to_edge(volume, extinction, p, sphere_direction(d, kSkyDirections));
            float scale = 1.0f;
            for (int k = 0; k < octaves; ++k, scale *= scattering.attenuation)
              visibility[k] += std::exp(-scale * depth) / float(kSkyDirections);
          }
          const float escape = visibility[0];
          const glm::vec3 carried = scattering.contribution * volume.albedo * (1.0f - escape);
          glm::vec3 sky(0.0f), weight(1.0f);
          for (int k = 0; k < octaves; ++k, weight *= carried) sky += weight * visibility[k];
          float* corner = grid.data() + 4 * (std::size_t(x) + std::size_t(corners.x) * (std::size_t(y) + std::size_t(corners.y) * z));
          corner[0] = sky.r, corner[1] = sky.g, corner[2] = sky.b, corner[3] = escape;
        }
  };
  const int threads = int(std::clamp(std::thread::hardware_concurrency(), 1u, 8u));
  std::vector<std::thread> workers;
  for (int i = 1; i < threads; ++i) workers.emplace_back(fill_slabs, i, threads);
  fill_slabs(0, threads);
  for (std::thread& worker : workers) worker.join();
  return grid;
}

glm::vec3 light_radiance(const Light& light, const glm::vec3& p, glm::vec3& to_light) {
  const glm::vec3 radiance = light.color * light.intensity;
  if (light.type == LightType::directional) {
    to_light = -glm::normalize(light.direction);
    return radiance;
  }
  const glm::vec3 d = light.position - p;
  const float distance2 = std::max(glm::dot(d, d), 1e-8f);
  to_light = d / std::sqrt(distance2);
  float window = 1.0f;
  if (light.range > 0.0f) {
    const float x = distance2 / (light.range * light.range);
    const float w = std::clamp(1.0f - x * x, 0.0f, 1.0f);
    window = w * w;
  }
  if (is_area_light(light.type)) {  // from its centre, as common/lights.glsl's area_light_share
    constexpr float kPi = 3.14159265f;
    float share = light.radius * light.radius / distance2;  // a sphere
    if (light.type != LightType::sphere) {
      float cos_emit = glm::dot(glm::normalize(light.direction), -to_light);
      if (light.two_sided) cos_emit = std::abs(cos_emit);
      const float area = light.type == LightType::rect ? light.size.x * light.size.y : kPi * light.radius * light.radius;
      share = area * std::max(cos_emit, 0.0f) / (kPi * distance2);
    }
    return radiance * window * std::min(share, 1.0f);
  }
  const float falloff = window / distance2;
  if (light.type == LightType::point) return radiance * falloff;
  const float cos_angle = glm::dot(-to_light, glm::normalize(light.direction));
  const float cone = glm::smoothstep(std::cos(light.outer_cone_angle), std::cos(light.inner_cone_angle), cos_angle);
  return radiance * cone * falloff;
}

PathTracedRay path_trace(const Volume& volume, std::span<const Light> lights, const glm::vec3& sky,
                         const glm::vec3& origin, const glm::vec3& direction, const PathTracing& tracing) {
  PathTracedRay ray;
  if (volume.nanovdb.empty() || !(volume.max_extinction() > 0.0f)) return ray;
  const glm::vec3 d = glm::normalize(direction);
  const auto [enter, exit] = ray_span(volume.world_bounds, origin, d);
  if (!(enter < exit)) return ray;
  ray.transmittance = transmittance(volume, origin + enter * d, origin + exit * d);
  Extinction extinction(volume);
  Random random(tracing.seed);
  glm::vec3 sum(0.0f);
  for (int path = 0; path < tracing.paths; ++path)
    sum += trace_path(volume, extinction, random, lights, sky, origin, d, tracing.max_bounces);
  ray.in_scattered = sum / float(std::max(tracing.paths, 1));
  return ray;
}

}  // namespace avsm::scene
