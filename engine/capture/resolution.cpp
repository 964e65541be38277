#include "capture/resolution.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>

#include "capture/files.h"
#include "capture/frame_report.h"
#include "capture/quality.h"

namespace avsm::capture {
namespace fs = std::filesystem;

const char* const kResolutionImageColours =
    "green: texel at most 1 pixel wide, yellow: at most 1.5, orange: at most 3, red: wider; dark blue: no lit receiver";

namespace {

// The colour of a receiver whose texel is `pixels` wide on screen.
void resolution_colour(float pixels, float* rgb) {
  static constexpr float kGreen[3] = {0.15f, 0.75f, 0.2f}, kYellow[3] = {0.95f, 0.85f, 0.1f},
                         kOrange[3] = {0.95f, 0.5f, 0.1f}, kRed[3] = {0.85f, 0.1f, 0.1f};
  const float* colour = pixels <= 1.0f ? kGreen : pixels <= kMatchedTexelPixels ? kYellow : pixels <= 3.0f ? kOrange : kRed;
  std::copy(colour, colour + 3, rgb);
}

void write_resolution_image(const fs::path& path, const passes::PixelShadowResolution* pixels, uint32_t width,
                            uint32_t height) {
  write_pixel_image(path, width, height, [&](size_t pixel, float* rgb) {
    if (pixels[pixel].level < 0.0f)
      std::copy(kNoReceiverColour, kNoReceiverColour + 3, rgb);
    else
      resolution_colour(pixels[pixel].texel_pixels, rgb);
  });
}

// The value below which `fraction` of the sorted values lie.
double quantile(const std::vector<float>& sorted, double fraction) {
  if (sorted.empty()) return 0.0;
  return sorted[std::min(sorted.size() - 1, size_t(fraction * double(sorted.size())))];
}

}  // namespace

std::string resolution_image_name(size_t light) { return "light" + std::to_string(light) + "_resolution.png"; }

uint64_t ResolutionReport::receivers() const {
  uint64_t sum = 0;
  for (const LightResolution& light : lights) sum += light.receivers;
  return sum;
}

uint64_t ResolutionReport::matched() const {
  uint64_t sum = 0;
  for (const LightResolution& light : lights) sum += light.matched;
  return sum;
}

double ResolutionReport::matched_fraction() const {
  const uint64_t all = receivers();
  return all ? double(matched()) / double(all) : 0.0;
}

ResolutionReport summarize_resolution(const std::vector<passes::PixelShadowResolution>& pixels, uint32_t width,
                                      uint32_t height, const scene::Scene& scene) {
  ResolutionReport report{width, height, {}};
  const size_t count = size_t(width) * height;
  for (size_t light = 0; light < scene.lights.size() && (light + 1) * count <= pixels.size(); ++light) {
    LightResolution figures{light_label(scene, light)};
    figures.levels.assign(kResolutionLevels, 0);
    std::vector<float> widths;
    for (size_t i = light * count; i < (light + 1) * count; ++i) {
      const passes::PixelShadowResolution& p = pixels[i];
      if (p.level < 0.0f) continue;
      figures.paged = figures.paged || p.paged != 0;
      figures.receivers += 1;
      figures.matched += p.texel_pixels <= kMatchedTexelPixels ? 1 : 0;
      figures.needed_texels += double(p.needed_texels);
      figures.levels[std::min(uint32_t(p.level), kResolutionLevels - 1)] += 1;
      widths.push_back(p.texel_pixels);
    }
    std::sort(widths.begin(), widths.end());
    figures.median_texel_pixels = quantile(widths, 0.5);
    figures.p95_texel_pixels = quantile(widths, 0.95);
    report.lights.push_back(std::move(figures));
  }
  return report;
}

ResolutionReport write_resolution(const fs::path& out_dir, const scene::Scene& scene,
                                  const std::vector<passes::PixelShadowResolution>& pixels, uint32_t width,
                                  uint32_t height) {
  ResolutionReport report = summarize_resolution(pixels, width, height, scene);
  const size_t count = size_t(width) * height;
  for (size_t i = 0; i < report.lights.size(); ++i)
    write_resolution_image(out_dir / resolution_image_name(i), pixels.data() + i * count, width, height);
  write_json(out_dir / "resolution.json", to_json(report));
  return report;
}

}  // namespace avsm::capture
