#include "capture/volume_comparison.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <vector>

#include "capture/files.h"

namespace avsm::capture {
namespace {

double luminance(const float* rgba) { return 0.2126 * rgba[0] + 0.7152 * rgba[1] + 0.0722 * rgba[2]; }

// A pixel the smoke changes by more than this fraction of its luminance is a smoke pixel.
constexpr double kSmokeChange = 0.01;

}  // namespace

VolumeShadingComparison compare_volume_shading(const gpu::ImageRGBA32F& fast, const gpu::ImageRGBA32F& reference,
                                               const gpu::ImageRGBA32F& hidden, gpu::ImageRGBA32F* error_image) {
  if (fast.width != reference.width || fast.height != reference.height || hidden.width != reference.width ||
      hidden.height != reference.height)
    throw std::invalid_argument("compare_volume_shading: the images differ in size");
  constexpr double kNotSmoke = -1.0;
  const double kNotFinite = std::numeric_limits<double>::quiet_NaN();
  VolumeShadingComparison result;
  std::vector<double> pixel_errors;  // |dL| per pixel, or one of the two markers
  std::vector<double> errors;        // the smoke pixels' |dL|
  double luminance_sum = 0.0;
  for (uint32_t y = 0; y < reference.height; ++y)
    for (uint32_t x = 0; x < reference.width; ++x) {
      const double fast_luminance = luminance(fast.at(x, y));
      const double with = luminance(reference.at(x, y)), without = luminance(hidden.at(x, y));
      if (!std::isfinite(fast_luminance)) {
        ++result.non_finite_pixels;
        pixel_errors.push_back(kNotFinite);
      } else if (std::abs(with - without) > kSmokeChange * std::max(with, without)) {
        errors.push_back(std::abs(fast_luminance - with));
        pixel_errors.push_back(errors.back());
        luminance_sum += with;
      } else {
        pixel_errors.push_back(kNotSmoke);
      }
    }
  result.smoke_pixels = errors.size();
  if (!errors.empty()) {
    result.mean_luminance = luminance_sum / double(errors.size());
    double sum = 0.0;
    for (double e : errors) sum += e;
    result.mean_abs_error = sum / double(errors.size());
    result.max_abs_error = *std::max_element(errors.begin(), errors.end());
    const size_t p99 = std::min(errors.size() - 1, size_t(std::ceil(0.99 * double(errors.size()))) - 1);
    std::nth_element(errors.begin(), errors.begin() + std::ptrdiff_t(p99), errors.end());
    result.p99_abs_error = errors[p99];
  }
  if (error_image) {
    *error_image = gpu::ImageRGBA32F{reference.width, reference.height, {}};
    for (double e : pixel_errors) {
      const float grey = result.mean_luminance > 0.0 ? float(std::min(e / result.mean_luminance * 10.0, 1.0)) : 0.0f;
      if (std::isnan(e))
        error_image->pixels.insert(error_image->pixels.end(), {1.0f, 0.0f, 0.0f, 1.0f});  // red: not a number
      else if (e == kNotSmoke)
        error_image->pixels.insert(error_image->pixels.end(), {0.0f, 0.0f, 0.15f, 1.0f});
      else
        error_image->pixels.insert(error_image->pixels.end(), {grey, grey, grey, 1.0f});
    }
  }
  return result;
}

void write_volume_comparison(const std::filesystem::path& file, const VolumeShadingComparison& c,
                             const std::string& fast_settings, const PassMedians& fast, const PassMedians& reference) {
  write_json(file, {{"fast_settings", fast_settings},
                    {"smoke_pixels", c.smoke_pixels},
                    {"smoke_pixel_rule", "the smoke changes the reference's luminance by more than 1%"},
                    {"mean_luminance", c.mean_luminance},
                    {"mean_abs_error", c.mean_abs_error},
                    {"p99_abs_error", c.p99_abs_error},
                    {"max_abs_error", c.max_abs_error},
                    {"non_finite_pixels", c.non_finite_pixels},
                    {"mean_relative", c.mean_relative()},
                    {"p99_relative", c.p99_relative()},
                    {"bound", {{"mean_relative", VolumeShadingComparison::kMeanBound},
                               {"p99_relative", VolumeShadingComparison::kP99Bound}}},
                    {"within_bound", c.within_bound()},
                    {"fast_gpu_ms", fast},
                    {"reference_gpu_ms", reference}});
}

}  // namespace avsm::capture
