#pragma once
// Writing captured frames: 8-bit sRGB PNG (stb) and linear float EXR (tinyexr).
#include <filesystem>
#include <string>

#include "gpu/transfer.h"

namespace avsm::io {

// Linear RGB in, sRGB-encoded 8-bit PNG out (values clamped to [0, 1]).
void write_png_srgb(const std::filesystem::path& path, const gpu::ImageRGBA32F& image);
// Values already display-ready (e.g. UNORM render targets, debug images): no encoding.
void write_png_raw(const std::filesystem::path& path, const gpu::ImageRGBA32F& image);
// Linear float RGBA, 32-bit channels.
void write_exr(const std::filesystem::path& path, const gpu::ImageRGBA32F& image);

// For tests: reads a PNG back as RGBA float in [0, 1] (no decoding) / an EXR as linear float.
gpu::ImageRGBA32F read_png(const std::filesystem::path& path);
gpu::ImageRGBA32F read_exr(const std::filesystem::path& path);

float linear_to_srgb(float linear);

}  // namespace avsm::io
