#pragma once
// Triangle meshes and their glTF metallic-roughness materials, as loaded from glTF.
#include "scene/bounds.h"

#include <glm/glm.hpp>

#include <algorithm>
#include <array>
#include <compare>
#include <cstdint>
#include <string>
#include <vector>

namespace avsm::scene {

// How a texture's bytes encode its values (glTF's convention per use): colours
// (base colour, emissive) are sRGB-encoded, data (metallic-roughness, normal,
// occlusion) is linear. The renderer samples them with an SRGB or a UNORM format.
enum class ColorSpace { srgb, linear };

// How a texture is read: glTF's sampler (wrapS/T, magFilter, minFilter). Without a
// sampler, or without a minFilter, glTF leaves the choice to the renderer: linear with
// linear mip blending (trilinear), repeating.
enum class TextureWrap { repeat, clamp_to_edge, mirrored_repeat };
enum class TextureFilter { nearest, linear };
struct TextureSampler {
  TextureWrap wrap_u = TextureWrap::repeat;
  TextureWrap wrap_v = TextureWrap::repeat;
  TextureFilter mag = TextureFilter::linear;
  TextureFilter min = TextureFilter::linear;
  bool mipmapped = true;                      // minification reads the mip chain
  TextureFilter mip = TextureFilter::linear;  // between mip levels (when mipmapped)
  auto operator<=>(const TextureSampler&) const = default;
};

// Decoded image, 4 bytes per pixel, rows top to bottom, with its mip chain when its
// sampler reads one (generated at load: a 2 x 2 box filter, in linear light for sRGB
// colours). One glTF image used both as a colour and as data, or through two samplers,
// becomes two textures.
struct Texture {
  std::string name;
  std::uint32_t width = 0;
  std::uint32_t height = 0;
  std::vector<std::uint8_t> rgba8;
  ColorSpace color_space = ColorSpace::srgb;
  TextureSampler sampler;
  // Levels 1, 2, ... down to 1 x 1, each half the one above (rounded down, at least 1);
  // empty when the sampler is not mipmapped.
  std::vector<std::vector<std::uint8_t>> mips;

  std::uint32_t mip_levels() const { return 1 + std::uint32_t(mips.size()); }
  std::uint32_t level_width(std::uint32_t level) const { return std::max(1u, width >> level); }
  std::uint32_t level_height(std::uint32_t level) const { return std::max(1u, height >> level); }
};

// Fills texture.mips from texture.rgba8: each level averages 2 x 2 texels of the one
// above (the last row or column of an odd size folds into its neighbour), in linear
// light for sRGB textures (averaging encoded values darkens), alpha linearly. The glTF
// loader calls it for textures whose sampler reads mips.
void generate_mips(Texture& texture);

enum class AlphaMode { opaque, mask, blend };

// glTF 2.0's metallic-roughness material; defaults are the specification's. Texture
// members index the texture list (-1 = none); every texture of a material is read
// through the mesh's one UV set (Mesh::uvs).
struct Material {
  std::string name;
  glm::vec4 base_color_factor{1.0f};  // linear RGBA, multiplies the texture
  int base_color_texture = -1;        // sRGB
  float metallic_factor = 1.0f;       // multiplies the texture's B channel
  float roughness_factor = 1.0f;      // multiplies the texture's G channel
  int metallic_roughness_texture = -1;  // linear: G roughness, B metallic
  int normal_texture = -1;            // linear, tangent space (+Y up in the image); needs Mesh::tangents
  float normal_scale = 1.0f;          // scales the sampled normal's X and Y
  int occlusion_texture = -1;         // linear, R channel
  float occlusion_strength = 1.0f;    // occlusion = 1 + strength x (R - 1)
  int emissive_texture = -1;          // sRGB, multiplies `emissive`
  AlphaMode alpha_mode = AlphaMode::opaque;
  float alpha_cutoff = 0.5f;          // used by AlphaMode::mask
  bool double_sided = false;
  glm::vec3 emissive{0.0f};           // emissiveFactor x KHR_materials_emissive_strength

  // Every texture member, in glTF's order (base colour, metallic-roughness, normal,
  // occlusion, emissive), for code that visits or renumbers them.
  std::array<int*, 5> textures() { return texture_members<int>(*this); }
  std::array<const int*, 5> textures() const { return texture_members<const int>(*this); }

 private:
  template <class Int, class Self>
  static std::array<Int*, 5> texture_members(Self& m) {
    return {&m.base_color_texture, &m.metallic_roughness_texture, &m.normal_texture, &m.occlusion_texture,
            &m.emissive_texture};
  }
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
  // Unit tangent (along +U) and handedness w (+-1): bitangent = cross(normal, tangent) x w
  // points up the image (-V in glTF's UVs). One per position when the material has a
  // normal texture (from the file's TANGENT, else generated), otherwise empty.
  std::vector<glm::vec4> tangents;
  std::vector<std::uint32_t> indices;  // 3 per triangle
  std::uint32_t material = 0;       // index into the material list
  Bounds bounds;

  std::size_t triangle_count() const { return indices.size() / 3; }
};

}  // namespace avsm::scene
