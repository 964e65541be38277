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
#include "passes/frame/view.h"
#include "scene/scene.h"

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

// The scene's volumes path traced on the CPU (scene::path_trace: every order of scattering,
// the lights and the sky, nothing else occluding), composited over `hidden` (the frame
// without them): what the fast path's multiple-scattering and sky terms are measured
// against (avsm-capture --path-trace-volumes). Rays run through the whole volume: where a
// surface cuts it, the composite sees smoke behind that surface too.
gpu::ImageRGBA32F path_trace_volumes(const scene::Scene& scene, const passes::View& view,
                                     const gpu::ImageRGBA32F& hidden, int paths);

// Mean luminance over the smoke pixels (those the path-traced frame changes by more than
// 1% against the hidden one) of the fast frame, the reference frame and the path-traced one.
struct PathTracedComparison {
  int paths = 0;
  uint64_t smoke_pixels = 0;
  double fast_luminance = 0.0, reference_luminance = 0.0, path_traced_luminance = 0.0;
  double fast_relative() const { return path_traced_luminance > 0.0 ? fast_luminance / path_traced_luminance - 1.0 : 0.0; }
};
PathTracedComparison compare_with_path_traced(const gpu::ImageRGBA32F& fast, const gpu::ImageRGBA32F& reference,
                                              const gpu::ImageRGBA32F& hidden, const gpu::ImageRGBA32F& path_traced,
                                              int paths);

// Per-pass median GPU ms of one path.
using PassMedians = std::map<std::string, double>;

// volume_quality.json: the figures, the bound, and both paths' pass medians.
// With `path_traced`, also its figures ("path_traced").
void write_volume_comparison(const std::filesystem::path& file, const VolumeShadingComparison& comparison,
                             const std::string& fast_settings, const PassMedians& fast,
                             const PassMedians& reference, const PathTracedComparison* path_traced = nullptr);

}  // namespace avsm::capture
