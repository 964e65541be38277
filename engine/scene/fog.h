#pragma once
// A homogeneous participating medium outside the volumes: one global fog filling all
// space, plus any number of axis-aligned fog boxes added to it where they are. The
// camera sees it through a froxel grid (passes/camera/fog/), lit by every light through
// its transmittance map, so that smoke, hair and meshes cast light shafts.
//
// Scene file: "fog": {"scattering", "absorption", "color", "phase_g", "sky_light",
// "boxes": [{"min", "max", "scattering", "absorption", "color", "phase_g"}], "froxel_pixels",
// "slices", "distance"}; scene/description.cpp checks each key and names the allowed range.
#include <glm/vec3.hpp>

#include <vector>

#include "scene/bounds.h"

namespace avsm::scene {

// The ranges the scene file (scene/description.cpp) and avsm::Shadows::set_fog hold a fog to.
inline constexpr float kFogMaxCoefficient = 100.0f;  // scattering, absorption: 0..this per metre
inline constexpr float kFogMaxPhaseG = 0.95f;        // phase_g: -this..this
inline constexpr float kFogMaxSkyLight = 4.0f;       // sky_light: 0..this
inline constexpr int kFogMinFroxelPixels = 4, kFogMaxFroxelPixels = 64;
inline constexpr int kFogMinSlices = 8, kFogMaxSlices = 256;

// Coefficients per world unit (metres). Extinction is grey: sigma_t = scattering + absorption;
// `color` tints the scattered light (a single-scattering albedo per channel of at most 1).
struct FogMedium {
  float scattering = 0.0f;
  float absorption = 0.0f;
  glm::vec3 color{1.0f};
  float phase_g = 0.0f;  // Henyey-Greenstein asymmetry, -0.95..0.95 (0: isotropic, > 0: forward)

  bool empty() const { return scattering <= 0.0f && absorption <= 0.0f; }
};

struct FogBox {
  Bounds bounds;
  FogMedium medium;
};

// The camera's froxel grid: `froxel_pixels` pixels a side on screen, `slices` slices in
// depth spread exponentially from the near plane to `distance` (0: to the scene's far side).
struct FogGrid {
  int froxel_pixels = 16;
  int slices = 64;
  float distance = 0.0f;
};

struct Fog {
  FogMedium global;
  std::vector<FogBox> boxes;
  float sky_light = 1.0f;  // scales the uniform sky (kSkyAmbient) the fog scatters, 0..4
  FogGrid grid;

  bool enabled() const {
    if (!global.empty()) return true;
    for (const FogBox& box : boxes)
      if (!box.medium.empty()) return true;
    return false;
  }
};

}  // namespace avsm::scene
