// A private copy of stb_image: STB_IMAGE_STATIC gives every stbi_* function
// internal linkage, so nothing here clashes with the stb_image that avsm_gpu
// compiles (PNG only, engine/io/image_io.cpp) or with libstb.so, which Debian's
// libtinygltf links; and this copy's configuration (PNG and JPEG, memory only)
// is the one glTF textures get, whatever else is linked.
#define STB_IMAGE_STATIC
#define STB_IMAGE_IMPLEMENTATION
#define STBI_ONLY_PNG
#define STBI_ONLY_JPEG
#define STBI_NO_STDIO
#define STBI_MAX_DIMENSIONS (1 << 15)
#include <stb/stb_image.h>

#include "scene/image_decode.h"

#include <algorithm>
#include <array>
#include <climits>
#include <cmath>

namespace avsm::scene::detail {

bool decode_rgba8(std::span<const unsigned char> encoded, std::uint32_t max_size, Texture& texture, std::string& error) {
  if (encoded.empty() || encoded.size() > std::size_t(INT_MAX)) {
    error = encoded.empty() ? "no data" : "too large";
    return false;
  }
  const int size = static_cast<int>(encoded.size());
  int width = 0, height = 0, channels = 0;
  if (!stbi_info_from_memory(encoded.data(), size, &width, &height, &channels)) {
    error = std::string("not a PNG or JPEG image stb_image can read (") + stbi_failure_reason() + ")";
    return false;
  }
  if (width <= 0 || height <= 0 || std::uint32_t(width) > max_size || std::uint32_t(height) > max_size) {
    error = std::to_string(width) + " x " + std::to_string(height) + " is outside 1 to " + std::to_string(max_size) + " per side";
    return false;
  }
  unsigned char* pixels = stbi_load_from_memory(encoded.data(), size, &width, &height, &channels, 4);
  if (pixels == nullptr) {
    error = std::string("decoding failed (") + stbi_failure_reason() + ")";
    return false;
  }
  texture.width = std::uint32_t(width);
  texture.height = std::uint32_t(height);
  texture.rgba8.assign(pixels, pixels + std::size_t(width) * std::size_t(height) * 4);
  stbi_image_free(pixels);
  return true;
}

}  // namespace avsm::scene::detail

namespace avsm::scene {

namespace {

float srgb_to_linear(float c) { return c <= 0.04045f ? c / 12.92f : std::pow((c + 0.055f) / 1.055f, 2.4f); }
float linear_to_srgb(float c) { return c <= 0.0031308f ? c * 12.92f : 1.055f * std::pow(c, 1.0f / 2.4f) - 0.055f; }

// The next level down: each texel the mean of the (up to 2 x 2, 3 x 3 at an odd edge)
// texels of `above` it covers, in the space `decode` maps bytes to.
std::vector<std::uint8_t> downsample(const std::vector<std::uint8_t>& above, std::uint32_t width, std::uint32_t height,
                                     bool srgb, const std::array<float, 256>& decode) {
  const std::uint32_t w = std::max(1u, width / 2), h = std::max(1u, height / 2);
  std::vector<std::uint8_t> below(std::size_t(w) * h * 4);
  for (std::uint32_t y = 0; y < h; ++y) {
    // The last texel takes the odd row or column left over, so no texel of `above` is lost.
    const std::uint32_t y0 = std::min(2 * y, height - 1), y1 = (y + 1 == h) ? height : std::min(2 * y + 2, height);
    for (std::uint32_t x = 0; x < w; ++x) {
      const std::uint32_t x0 = std::min(2 * x, width - 1), x1 = (x + 1 == w) ? width : std::min(2 * x + 2, width);
      float sum[4] = {0, 0, 0, 0};
      for (std::uint32_t sy = y0; sy < y1; ++sy)
        for (std::uint32_t sx = x0; sx < x1; ++sx) {
          const std::uint8_t* texel = &above[(std::size_t(sy) * width + sx) * 4];
          for (int c = 0; c < 3; ++c) sum[c] += decode[texel[c]];
          sum[3] += texel[3] / 255.0f;
        }
      const float count = float((y1 - y0) * (x1 - x0));
      std::uint8_t* out = &below[(std::size_t(y) * w + x) * 4];
      for (int c = 0; c < 4; ++c) {
        const float mean = sum[c] / count;
        const float encoded = (srgb && c < 3) ? linear_to_srgb(mean) : mean;
        out[c] = std::uint8_t(std::lround(std::clamp(encoded, 0.0f, 1.0f) * 255.0f));
      }
    }
  }
  return below;
}

}  // namespace

void generate_mips(Texture& texture) {
  const bool srgb = texture.color_space == ColorSpace::srgb;
  std::array<float, 256> decode;
  for (int i = 0; i < 256; ++i) decode[i] = srgb ? srgb_to_linear(i / 255.0f) : i / 255.0f;
  texture.mips.clear();
  std::uint32_t width = texture.width, height = texture.height;
  const std::vector<std::uint8_t>* above = &texture.rgba8;
  while (width > 1 || height > 1) {
    texture.mips.push_back(downsample(*above, width, height, srgb, decode));
    above = &texture.mips.back();
    width = std::max(1u, width / 2);
    height = std::max(1u, height / 2);
  }
}

}  // namespace avsm::scene
