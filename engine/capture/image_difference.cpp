#include "capture/image_difference.h"

#include <cmath>
#include <limits>
#include <stdexcept>
#include <string>

#include "io/image_io.h"

namespace avsm::capture {

namespace {

double compressed(float value) { return value > 0 ? double(value) / (1.0 + double(value)) : 0.0; }

double channel_difference(float image, float reference) {
  if (std::isfinite(image) && std::isfinite(reference)) return compressed(image) - compressed(reference);
  return (image == reference || (std::isnan(image) && std::isnan(reference))) ? 0.0 : 1.0;
}

std::string size_text(const gpu::ImageRGBA32F& image) {
  return std::to_string(image.width) + "x" + std::to_string(image.height);
}
}  // namespace

ImageDifference image_difference(const gpu::ImageRGBA32F& image, const gpu::ImageRGBA32F& reference) {
  if (image.width != reference.width || image.height != reference.height)
    throw std::invalid_argument("image is " + size_text(image) + ", its reference " + size_text(reference) +
                                ": only images of one size compare (give both captures the same --width and --height)");
  const size_t pixels = size_t(image.width) * image.height;
  double abs_sum = 0, squared_sum = 0;
  for (size_t p = 0; p < pixels; ++p)
    for (size_t c = 0; c < 3; ++c) {
      const double d = channel_difference(image.pixels[p * 4 + c], reference.pixels[p * 4 + c]);
      abs_sum += std::abs(d);
      squared_sum += d * d;
    }
  const double samples = double(pixels) * 3;
  ImageDifference difference;
  if (samples == 0) return difference;
  difference.mean_abs_error = abs_sum / samples;
  const double mse = squared_sum / samples;
  difference.psnr_db = mse > 0 ? -10.0 * std::log10(mse) : std::numeric_limits<double>::infinity();
  return difference;
}

ImageDifference exr_difference(const std::filesystem::path& image, const std::filesystem::path& reference) {
  const gpu::ImageRGBA32F a = io::read_exr(image), b = io::read_exr(reference);
  try {
    return image_difference(a, b);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(image.string() + " against " + reference.string() + ": " + e.what());
  }
}

}  // namespace avsm::capture
