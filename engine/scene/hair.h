#pragma once
// Hair as the renderer wants it: one point array, strands as ranges of it, and
// one width / opacity / colour per strand. Readers for TressFX 3 and 4 (.tfx) and
// Cem Yuksel's cyHair (.hair); glTF line primitives come from gltf.h.
#include "scene/bounds.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <span>
#include <string>
#include <vector>

namespace avsm::scene {

// What strand_width holds. cyHair stores real thicknesses (absolute, in the
// units of the points); TressFX and glTF do not, so their strand_width is a
// multiplier (1 unless the file has per-strand factors) that the scene file's
// "width" scales.
enum class StrandWidth { absolute, relative };

// Defaults used where a file says nothing about opacity or colour.
inline constexpr float kDefaultStrandOpacity = 1.0f;
inline constexpr glm::vec3 kDefaultStrandColor{0.35f, 0.22f, 0.12f};

struct HairGroom {
  std::string name;
  std::vector<glm::vec3> points;
  // Strand s is points[strand_offsets[s] .. strand_offsets[s + 1]); size = strands + 1.
  std::vector<std::uint32_t> strand_offsets;
  std::vector<float> strand_width;       // see width_kind
  std::vector<float> strand_opacity;     // in [0, 1]; 1 = one fibre blocks all light
  std::vector<glm::vec3> strand_color;   // linear RGB
  StrandWidth width_kind = StrandWidth::relative;
  Bounds bounds;                         // of the points

  std::size_t strand_count() const { return strand_offsets.empty() ? 0 : strand_offsets.size() - 1; }
  std::size_t strand_size(std::size_t strand) const {
    return strand_offsets[strand + 1] - strand_offsets[strand];
  }
};

// Upper bound on hair files, far above any real groom; protects against
// accidental multi-gigabyte reads.
inline constexpr std::uint64_t kMaxHairFileBytes = 1ull << 31;

// TressFX (.tfx), the layout chosen by the header's float version:
// 3.x "TressFXFileObject": a 296-byte header (strand count, vertices per
//   strand, byte offsets), float3 positions, optional per-strand thickness
//   factors and per-vertex RGBA colours;
// 4.x "TressFXTFXFileHeader": a 160-byte header with the same counts and the
//   offsets of float4 positions (w, the simulation's inverse mass, is ignored),
//   per-strand and per-vertex UVs (checked to lie in the file, not kept),
//   per-strand thickness factors and per-vertex RGBA colours.
// Colours are averaged per strand; missing thickness is 1, missing colour
// kDefaultStrandColor.
HairGroom load_tfx(const std::filesystem::path& file);
HairGroom parse_tfx(std::span<const std::byte> bytes, const std::filesystem::path& name);
enum class TfxVersion { v3, v4 };
// Writes positions (and the thickness factors if not all 1). Every strand must
// have the same number of points, 2 to 64. Version 4 positions get w = 0 on
// each strand's root and 1 elsewhere (TressFX's pinned root).
std::vector<std::byte> encode_tfx(const HairGroom& groom, TfxVersion version = TfxVersion::v3);

// cyHair (.hair): a 128-byte header "HAIR" with counts, a bit field of present
// arrays and defaults, then segments (uint16 per strand), points (float3),
// thickness, transparency (float per point) and colour (float3 per point).
// Per-point thickness / transparency / colour are averaged per strand.
HairGroom load_cyhair(const std::filesystem::path& file);
HairGroom parse_cyhair(std::span<const std::byte> bytes, const std::filesystem::path& name);
// Writes segments, points and per-point thickness, transparency and colour
// (each strand's value repeated on its points). Strands may differ in length.
std::vector<std::byte> encode_cyhair(const HairGroom& groom);

// Applies a placement: points by `transform`; absolute widths by its uniform
// scale (cube root of |det|).
void transform_groom(HairGroom& groom, const glm::mat4& transform);

// Throws LoadError naming `file` unless the groom is consistent: offsets
// increasing and matching the points, per-strand arrays of the right size,
// finite positions, widths >= 0, opacity in [0, 1], colours finite and >= 0.
// Also (re)computes bounds. Every loader calls it before returning.
void validate_groom(HairGroom& groom, const std::filesystem::path& file);

}  // namespace avsm::scene
