#include "capture/volume_comparison.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <stdexcept>
#include <thread>
#include <vector>

#include "capture/files.h"
#include "scene/volume_scattering.h"
#include "shared/lights.h"

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

gpu::ImageRGBA32F path_trace_volumes(const scene::Scene& scene, const passes::View& view,
                                     const gpu::ImageRGBA32F& hidden, int paths) {
  if (hidden.width != view.width || hidden.height != view.height)
    throw std::invalid_argument("path_trace_volumes: the hidden frame is not the view's size");
  const glm::vec3 sky = shared::kSkyAmbient;
  gpu::ImageRGBA32F image = hidden;
  auto trace_rows = [&](uint32_t first, uint32_t stride) {
    for (uint32_t y = first; y < view.height; y += stride)
      for (uint32_t x = 0; x < view.width; ++x) {
        const passes::Ray camera_ray = passes::pixel_ray(view, glm::vec2(x, y));
        // Volumes front to back by where the ray enters their bounds (they rarely overlap).
        std::vector<std::pair<float, const scene::Volume*>> hit;
        for (const scene::Volume& volume : scene.volumes) {
          const auto [enter, leave] = scene::ray_span(volume.world_bounds, camera_ray.origin, camera_ray.direction);
          if (enter < leave) hit.emplace_back(enter, &volume);
        }
        std::sort(hit.begin(), hit.end(), [](const auto& l, const auto& r) { return l.first < r.first; });
        glm::vec3 in_scattered(0.0f);
        float transmittance = 1.0f;
        for (const auto& [enter, volume] : hit) {
          const scene::PathTracedRay ray = scene::path_trace(
              *volume, scene.lights, sky * volume->sky_light, camera_ray.origin, camera_ray.direction,
              {paths, 256, 1u + y * view.width + x});
          in_scattered += transmittance * ray.in_scattered;
          transmittance *= ray.transmittance;
        }
        float* pixel = image.pixels.data() + (size_t(y) * view.width + x) * 4;
        for (int c = 0; c < 3; ++c) pixel[c] = pixel[c] * transmittance + in_scattered[c];
      }
  };
  const uint32_t threads = std::clamp(std::thread::hardware_concurrency(), 1u, 16u);
  std::vector<std::thread> workers;
  for (uint32_t i = 1; i < threads; ++i) workers.emplace_back(trace_rows, i, threads);
  trace_rows(0, threads);
  for (std::thread& worker : workers) worker.join();
  return image;
}

PathTracedComparison compare_with_path_traced(const gpu::ImageRGBA32F& fast, const gpu::ImageRGBA32F& reference,
                                              const gpu::ImageRGBA32F& hidden, const gpu::ImageRGBA32F& path_traced,
                                              int paths) {
  PathTracedComparison result;
  result.paths = paths;
  for (uint32_t y = 0; y < hidden.height; ++y)
    for (uint32_t x = 0; x < hidden.width; ++x) {
      const double traced = luminance(path_traced.at(x, y)), without = luminance(hidden.at(x, y));
      if (!(std::abs(traced - without) > kSmokeChange * std::max(traced, without))) continue;
      ++result.smoke_pixels;
      result.path_traced_luminance += traced;
      result.fast_luminance += luminance(fast.at(x, y));
      result.reference_luminance += luminance(reference.at(x, y));
    }
  if (result.smoke_pixels > 0) {
    result.path_traced_luminance /= double(result.smoke_pixels);
    result.fast_luminance /= double(result.smoke_pixels);
    result.reference_luminance /= double(result.smoke_pixels);
  }
  return result;
}

void write_volume_comparison(const std::filesystem::path& file, const VolumeShadingComparison& c,
                             const std::string& fast_settings, const PassMedians& fast, const PassMedians& reference,
                             const PathTracedComparison* path_traced) {
  nlohmann::json traced = nullptr;
  if (path_traced)
    traced = {{"paths_per_pixel", path_traced->paths},
              {"smoke_pixels", path_traced->smoke_pixels},
              {"smoke_pixel_rule", "the path-traced smoke changes the luminance by more than 1%"},
              {"fast_mean_luminance", path_traced->fast_luminance},
              {"reference_mean_luminance", path_traced->reference_luminance},
              {"path_traced_mean_luminance", path_traced->path_traced_luminance},
              {"fast_relative", path_traced->fast_relative()}};
  write_json(file, {{"fast_settings", fast_settings},
                    {"path_traced", traced},
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
