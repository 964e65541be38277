// Frame against frame (capture/image_difference.h): mean absolute error and PSNR of the
// RGB mapped by x / (1 + x), through frame.exr files as the sweep report reads them.
#include "capture/image_difference.h"

#include <gtest/gtest.h>

#include <cmath>
#include <filesystem>
#include <stdexcept>

#include "io/image_io.h"

namespace avsm::capture {
namespace image_difference_test {  // one per file: test targets are unity builds
namespace {
namespace fs = std::filesystem;

gpu::ImageRGBA32F filled(uint32_t width, uint32_t height, float value) {
  gpu::ImageRGBA32F image{width, height, std::vector<float>(size_t(width) * height * 4, value)};
  return image;
}

TEST(ImageDifference, KnownErrorsAndPsnr) {
  gpu::ImageRGBA32F reference = filled(4, 2, 0.5f);
  gpu::ImageRGBA32F image = reference;
  image.at(1, 1)[0] = 1.0f;  // one channel of one pixel: 1/3 -> 1/2 mapped (alpha does not count)
  image.at(3, 0)[3] = 0.0f;
  const ImageDifference d = image_difference(image, reference);
  const double off = 0.5 - 1.0 / 3.0;
  EXPECT_NEAR(d.mean_abs_error, off / 24, 1e-7);
  EXPECT_NEAR(d.psnr_db, -10 * std::log10(off * off / 24), 1e-5);
  EXPECT_TRUE(std::isinf(image_difference(reference, reference).psnr_db));
  EXPECT_EQ(image_difference(reference, reference).mean_abs_error, 0.0);
}

TEST(ImageDifference, ExrFilesOfDifferentSizesAreRefusedNamingBoth) {
  const fs::path dir = fs::path(testing::TempDir()) / "image_difference";
  fs::create_directories(dir);
  io::write_exr(dir / "a.exr", filled(4, 2, 0.25f));
  io::write_exr(dir / "b.exr", filled(4, 2, 0.75f));
  io::write_exr(dir / "c.exr", filled(2, 4, 0.25f));
  EXPECT_NEAR(exr_difference(dir / "a.exr", dir / "b.exr").mean_abs_error, 0.75 / 1.75 - 0.25 / 1.25, 1e-6);
  try {
    exr_difference(dir / "a.exr", dir / "c.exr");
    FAIL() << "sizes 4x2 and 2x4 compared";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("a.exr against"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("c.exr"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("--width"), std::string::npos) << e.what();
  }
  EXPECT_THROW(exr_difference(dir / "missing.exr", dir / "a.exr"), std::runtime_error);
}

}  // namespace
}  // namespace image_difference_test
}  // namespace avsm::capture
