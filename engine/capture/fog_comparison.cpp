#include "capture/fog_comparison.h"

#include <cmath>
#include <stdexcept>

#include <nlohmann/json.hpp>

#include "capture/files.h"

namespace avsm::capture {

FogComparison compare_fog(const gpu::ImageRGBA32F& fast, const gpu::ImageRGBA32F& reference,
                          const gpu::ImageRGBA32F& without_fog) {
  if (fast.pixels.size() != reference.pixels.size() || fast.pixels.size() != without_fog.pixels.size())
    throw std::invalid_argument("compare_fog: the images differ in size");
  FogComparison c;
  for (size_t pixel = 0; pixel < fast.pixels.size() / 4; ++pixel) {
    bool fogged = false, finite = true;
    for (size_t channel = 0; channel < 3; ++channel) {
      const size_t i = pixel * 4 + channel;
      finite = finite && std::isfinite(fast.pixels[i]);
      const double effect = std::abs(double(reference.pixels[i]) - without_fog.pixels[i]);
      if (effect <= 0.01 * std::abs(double(reference.pixels[i]))) continue;
      fogged = true;
      c.fog_effect += effect;
      c.difference += std::abs(double(fast.pixels[i]) - reference.pixels[i]);
    }
    c.fogged_pixels += fogged;
    c.non_finite_pixels += !finite;
  }
  return c;
}

void write_fog_comparison(const std::filesystem::path& file, const FogComparison& c) {
  write_json(file, {{"fogged_pixels", c.fogged_pixels},
                    {"fog_effect", c.fog_effect},
                    {"difference", c.difference},
                    {"relative_l1", c.relative_l1()},
                    {"non_finite_pixels", c.non_finite_pixels},
                    {"bound", FogComparison::kBound},
                    {"within_bound", c.within_bound()}});
}

}  // namespace avsm::capture
