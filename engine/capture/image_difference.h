#pragma once
// How far one captured frame is from another: the mean absolute error and the PSNR of
// their linear RGB (frame.exr), what the sweep report shows of each job against its
// reference job.
#include <filesystem>

#include "gpu/transfer.h"

namespace avsm::capture {

// Both figures are over every pixel's R, G and B mapped by x / (1 + x) into [0, 1):
// frame.exr holds linear HDR (the default scene reaches 4), and this brings it into a
// peak of 1 without a display curve's clamp, so highlights still count but cannot swamp
// the rest of the image. A value that is not finite (NaN, inf) differs by the whole
// range from anything but itself.
struct ImageDifference {
  double mean_abs_error = 0;
  double psnr_db = 0;  // peak 1; +infinity when the images are equal
};

// Alpha is left out (the frame's is constant). Throws std::invalid_argument when the
// sizes differ.
ImageDifference image_difference(const gpu::ImageRGBA32F& image, const gpu::ImageRGBA32F& reference);

// Reads both EXRs. Throws std::runtime_error naming the files when one cannot be read or
// their sizes differ.
ImageDifference exr_difference(const std::filesystem::path& image, const std::filesystem::path& reference);

}  // namespace avsm::capture
