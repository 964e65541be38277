#pragma once
// How well the shadow maps' resolution matches the camera's, on the CPU side of
// avsm-capture --measure-resolution: the per-pixel figures of
// passes/camera/quality/shadow_resolution_pass.h summed up per light into
// resolution.json, and light<i>_resolution.png per light. The paged maps' target
// (issue 33): at >= 95% of lit receiver pixels, the texel a lookup reads is at most
// kMatchedTexelPixels screen pixels wide.
#include <cstdint>
#include <filesystem>
#include <string>
#include <vector>

#include "passes/camera/quality/shadow_resolution_pass.h"
#include "scene/scene.h"

namespace avsm::capture {

inline constexpr float kMatchedTexelPixels = shared::kPagedTexelPixels;
// Receivers are counted per level read, up to this many levels (coarser ones in the last).
inline constexpr uint32_t kResolutionLevels = 12;

// What the receivers' texel widths are coloured by in light<i>_resolution.png.
extern const char* const kResolutionImageColours;

struct LightResolution {
  std::string light;  // name, or "light <i>"
  bool paged = false;
  uint64_t receivers = 0;  // lit receiver pixels (shadow_resolution.comp says which count)
  uint64_t matched = 0;    // of them, those whose texel is at most kMatchedTexelPixels wide
  double median_texel_pixels = 0.0, p95_texel_pixels = 0.0;
  // The texels a map whose texels just meet kMatchedTexelPixels at every receiver would
  // spend on them (PixelShadowResolution::needed_texels): the least any square-texel map
  // needs, which the receivers' anisotropy sets.
  double needed_texels = 0.0;
  std::vector<uint64_t> levels;  // receivers per level read (rounded down), kResolutionLevels
  double matched_fraction() const { return receivers ? double(matched) / double(receivers) : 0.0; }
};

// resolution.json: every light's figures over a width x height frame, and all lights'
// receivers together.
struct ResolutionReport {
  uint32_t width = 0, height = 0;
  std::vector<LightResolution> lights;  // light i's image: resolution_image_name(i)
  uint64_t receivers() const;
  uint64_t matched() const;
  double matched_fraction() const;
};
std::string resolution_image_name(size_t light);  // light<i>_resolution.png

// Sums the per-pixel figures (ShadowResolutionPass::results(), one light after another
// over a width x height image) per light.
ResolutionReport summarize_resolution(const std::vector<passes::PixelShadowResolution>& pixels, uint32_t width,
                                      uint32_t height, const scene::Scene& scene);

// Writes resolution.json and light<i>_resolution.png into out_dir; returns what
// resolution.json holds.
ResolutionReport write_resolution(const std::filesystem::path& out_dir, const scene::Scene& scene,
                                  const std::vector<passes::PixelShadowResolution>& pixels, uint32_t width,
                                  uint32_t height);

}  // namespace avsm::capture
