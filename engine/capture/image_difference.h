#pragma once
// How far one captured frame is from another: the mean absolute error and the PSNR of
// their linear RGB (frame.exr), what the sweep report shows of each job against its
// reference job.
#include <filesystem>

#include "gpu/transfer.h"

namespace avsm::capture {

struct ImageDifference {
  double mean_abs_error = 0;  // over every pixel's R, G and B
  double psnr_db = 0;         // peak 1 (linear white); +infinity when the images are equal
};

// Alpha is left out (the frame's is constant). Throws std::invalid_argument when the
// sizes differ.
ImageDifference image_difference(const gpu::ImageRGBA32F& image, const gpu::ImageRGBA32F& reference);

// Reads both EXRs. Throws std::runtime_error naming the files when one cannot be read or
// their sizes differ.
ImageDifference exr_difference(const std::filesystem::path& image, const std::filesystem::path& reference);

}  // namespace avsm::capture
