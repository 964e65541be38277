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

#include <climits>

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
