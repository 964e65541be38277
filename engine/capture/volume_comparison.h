#pragma once
// The fast volume shading measured against the reference (avsm-capture
// --compare-volume-shading): the same view rendered with each, and once with the
// volumes hidden from the camera (they still cast shadows) to find the smoke pixels,
// those whose luminance the smoke changes by more than 1%. On linear HDR luminance:
// mean |L_fast - L_reference| over the smoke pixels and its 99th percentile, each
// relative to the reference's mean luminance there. The bound the fast path is held
// to: mean <= 2%, 99th percentile <= 10%.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>

#include "gpu/transfer.h"

namespace avsm::capture {

struct VolumeShadingComparison {
  static constexpr double kMeanBound = 0.02;
  static constexpr double kP99Bound = 0.10;
  uint64_t smoke_pixels = 0;
  double mean_luminance = 0.0;     // of the reference, over the smoke pixels
  double mean_abs_error = 0.0;     // |L_fast - L_reference|
  double p99_abs_error = 0.0;
  double max_abs_error = 0.0;
  uint64_t non_finite_pixels = 0;  // of the fast image, anywhere: never within the bound
  double mean_relative() const { return mean_luminance > 0.0 ? mean_abs_error / mean_luminance : 0.0; }
  double p99_relative() const { return mean_luminance > 0.0 ? p99_abs_error / mean_luminance : 0.0; }
  bool within_bound() const {
    return non_finite_pixels == 0 && mean_relative() <= kMeanBound && p99_relative() <= kP99Bound;
  }
};

// The three images must have one size. `error_image` (optional) gets |dL| / mean
// luminance x 10 in grey (white: 10% or more), dim blue outside the smoke, red where
// the fast image is not finite.
VolumeShadingComparison compare_volume_shading(const gpu::ImageRGBA32F& fast, const gpu::ImageRGBA32F& reference,
                                               const gpu::ImageRGBA32F& hidden, gpu::ImageRGBA32F* error_image = nullptr);

// Per-pass median GPU ms of one path.
using PassMedians = std::map<std::string, double>;

// volume_quality.json: the figures, the bound, and both paths' pass medians.
void write_volume_comparison(const std::filesystem::path& file, const VolumeShadingComparison& comparison,
                             const std::string& fast_settings, const PassMedians& fast,
                             const PassMedians& reference);

}  // namespace avsm::capture
