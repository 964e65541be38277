#pragma once
// Internal: PNG / JPEG (glTF's core image formats) to RGBA8.
#include "scene/mesh.h"

#include <cstddef>
#include <cstdint>
#include <span>
#include <string>

namespace avsm::scene::detail {

// Decodes into `texture` (width, height, rgba8); on failure returns false and
// says why in `error`. Images larger than max_size per side are refused from
// their header, before any pixel is decoded.
bool decode_rgba8(std::span<const unsigned char> encoded, std::uint32_t max_size, Texture& texture, std::string& error);

}  // namespace avsm::scene::detail
