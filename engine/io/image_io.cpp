#include "io/image_io.h"

#include <tinyexr.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>
#include <vector>

#define STB_IMAGE_WRITE_IMPLEMENTATION
#include <stb/stb_image_write.h>
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#include <stb/stb_image.h>

namespace avsm::io {

float linear_to_srgb(float linear) {
  linear = std::clamp(linear, 0.0f, 1.0f);
  return linear <= 0.0031308f ? linear * 12.92f : 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
}

static void write_png(const std::filesystem::path& path, const gpu::ImageRGBA32F& image, bool encode_srgb) {
  std::vector<uint8_t> bytes(image.pixels.size());
  for (size_t i = 0; i < image.pixels.size(); ++i) {
    float v = image.pixels[i];
    bool is_alpha = i % 4 == 3;
    if (encode_srgb && !is_alpha) v = linear_to_srgb(v);
    bytes[i] = uint8_t(std::lround(std::clamp(v, 0.0f, 1.0f) * 255.0f));
  }
  if (!stbi_write_png(path.string().c_str(), int(image.width), int(image.height), 4, bytes.data(),
                      int(image.width) * 4))
    throw std::runtime_error(path.string() + ": cannot write PNG");
}

void write_png_srgb(const std::filesystem::path& path, const gpu::ImageRGBA32F& image) { write_png(path, image, true); }
void write_png_raw(const std::filesystem::path& path, const gpu::ImageRGBA32F& image) { write_png(path, image, false); }

void write_exr(const std::filesystem::path& path, const gpu::ImageRGBA32F& image) {
  const char* error = nullptr;
  int result = SaveEXR(image.pixels.data(), int(image.width), int(image.height), 4, /*save_as_fp16=*/0,
                       path.string().c_str(), &error);
  if (result != TINYEXR_SUCCESS) {
    std::string message = path.string() + ": cannot write EXR: " + (error ? error : "unknown error");
    if (error) FreeEXRErrorMessage(error);
    throw std::runtime_error(message);
  }
}

gpu::ImageRGBA32F read_png(const std::filesystem::path& path) {
  int w = 0, h = 0, channels = 0;
  uint8_t* data = stbi_load(path.string().c_str(), &w, &h, &channels, 4);
  if (!data) throw std::runtime_error(path.string() + ": cannot read PNG: " + stbi_failure_reason());
  gpu::ImageRGBA32F out{uint32_t(w), uint32_t(h), std::vector<float>(size_t(w) * h * 4)};
  for (size_t i = 0; i < out.pixels.size(); ++i) out.pixels[i] = data[i] / 255.0f;
  stbi_image_free(data);
  return out;
}

gpu::ImageRGBA32F read_exr(const std::filesystem::path& path) {
  float* data = nullptr;
  int w = 0, h = 0;
  const char* error = nullptr;
  if (LoadEXR(&data, &w, &h, path.string().c_str(), &error) != TINYEXR_SUCCESS) {
    std::string message = path.string() + ": cannot read EXR: " + (error ? error : "unknown error");
    if (error) FreeEXRErrorMessage(error);
    throw std::runtime_error(message);
  }
  gpu::ImageRGBA32F out{uint32_t(w), uint32_t(h), std::vector<float>(data, data + size_t(w) * h * 4)};
  free(data);
  return out;
}

}  // namespace avsm::io
