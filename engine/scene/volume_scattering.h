#pragma once
// Light in a fog volume beyond single scattering, on the CPU:
// - the sky lighting grid the GPU's volume lighting reads (shaders/common/scattered_light.glsl):
//   how much of a uniform sky each majorant-brick corner scatters, through the volume itself,
//   and how likely light scattered there is to leave the volume unscattered;
// - a Monte Carlo path tracer of one volume (every order of scattering, isotropic phase,
//   lights and sky by next-event estimation), the reference that the octave approximation
//   (MultipleScattering) and the sky term are measured against (tests/passes, bench/media).
#include "scene/light.h"
#include "scene/volume.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <span>
#include <vector>

namespace avsm::scene {

// Directions the sky lighting averages over (spread evenly over the sphere).
inline constexpr int kSkyDirections = 16;

// Per corner of the volume's majorant bricks ((dims + 1)^3 corners, x fastest), four floats:
// - rgb: the radiance a uniform sky of radiance 1 scatters there per unit sigma_s, over
//   the octaves of its MultipleScattering: the sum over k of weight_k times the mean over
//   the sphere of exp(-attenuation^k * optical depth to the volume's edge), weight_k being
//   (contribution * albedo * (1 - escape))^k;
// - a: escape, the chance that light scattered there leaves the volume before it scatters
//   again: the mean transmittance over the sphere (octave 0's visibility).
// Sky light is soft, so bricks are fine enough. The GPU interpolates them trilinearly.
std::vector<float> sky_lighting(const Volume& volume);
std::size_t sky_lighting_corners(const Volume& volume);

// Radiance arriving at `p` from `light` (unshadowed), and the unit vector towards it: the
// renderer's light_radiance() (shaders/common/lights.glsl) on the CPU.
glm::vec3 light_radiance(const Light& light, const glm::vec3& p, glm::vec3& to_light);

struct PathTracedRay {
  glm::vec3 in_scattered{0.0f};  // radiance the volume scatters towards the ray's origin
  float transmittance = 1.0f;    // through the whole volume along the ray
};

struct PathTracing {
  int paths = 64;        // per ray
  int max_bounces = 256; // scattering events per path (Russian roulette ends most sooner)
  std::uint32_t seed = 1;
};

// Every order of scattering along a ray through `volume` alone (nothing else occludes):
// delta tracking against the volume's largest extinction, lights and a uniform sky of
// radiance `sky` by next-event estimation with ratio-tracked transmittance. Thread-safe.
PathTracedRay path_trace(const Volume& volume, std::span<const Light> lights, const glm::vec3& sky,
                         const glm::vec3& origin, const glm::vec3& direction, const PathTracing& tracing);

}  // namespace avsm::scene
