#pragma once
// Triangle meshes and their base-colour materials, as loaded from glTF.
#include "scene/bounds.h"

#include <glm/glm.hpp>

#include <cstdint>
#include <string>
#include <vector>

namespace avsm::scene {

// Decoded image, 4 bytes per pixel, rows top to bottom. Base-colour textures
// hold sRGB-encoded values (glTF's convention): sample them with an sRGB format.
struct Texture {
  std::string name;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgba8;
};

enum class AlphaMode { opaque, mask, blend };

struct Material {
  std::string name;
  glm::vec4 base_color_factor{1.0f};  // linear RGBA, multiplies the texture
  int base_color_texture = -1;        // index into the texture list, -1 = none
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;          // used by AlphaMode::mask
  bool double_sided = false;
  glm::vec3 emissive{0.0f};           // emissiveFactor x KHR_materials_emissive_strength
};

// What to do when a glTF primitive has no normals. The glTF spec asks for flat
// normals (each triangle gets its own three vertices); smooth averages the
// area-weighted face normals at shared vertices.
enum class NormalGeneration { flat, smooth };

// One triangle list with one material. Positions and normals are already in the
// space the loader was asked for (glTF node hierarchy and placement applied),
// triangles are counter-clockwise seen from the front even under mirroring
// transforms.
struct Mesh {
  std::string name;                 // the glTF node's name, else its mesh's; "#<primitive>" when several
  std::vector<glm::vec3> positions;
  std::vector<glm::vec3> normals;   // unit length, one per position
  std::vector<glm::vec2> uvs;       // one per position, or empty when the primitive has none
  std::vector<std::uint32_t> indices;  // 3 per triangle
  std::uint32_t material = 0;       // index into the material list
  Bounds bounds;

  std::size_t triangle_count() const { return indices.size() / 3; }
};

}  // namespace avsm::scene
