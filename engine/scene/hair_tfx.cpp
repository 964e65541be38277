// TressFX 3 .tfx ("TressFXFileObject", AMD TressFX 3.x TressFXFileFormat.h):
//   0  float version                  (3.x)
//   4  uint  numGuideHairStrands
//   8  uint  numVerticesPerStrand     (same for all strands)
//  12  uint  numFollowHairsPerGuideHair (follow hairs are generated at run time; ignored)
//  16  BOOL  bothEndsImmovable        (simulation only; ignored)
//  20  uint  reserved1[31]
// 144  uint  verticesOffset           float3 per vertex
// 148  uint  perStrandThicknessOffset float per strand, 0 = absent
// 152  uint  perStrandTexCoordOffset  (ignored)
// 156  uint  perVertexColorOffset     float4 per vertex, 0 = absent
// 160  uint  guideHairStrandOffset    (ignored)
// 164  uint  perVertexTexCoordOffset  (ignored)
// 168  uint  reserved2[32]
// 296  data; offsets are from the start of the file.
#include "scene/binary_reader.h"
#include "scene/hair.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace avsm::scene {
namespace {

constexpr std::size_t kHeaderBytes = 296;
constexpr std::size_t kOffsetsAt = 144;
constexpr std::uint32_t kMaxVerticesPerStrand = 64;

struct TfxHeader {
  float version = 0;
  std::uint32_t strands = 0;
  std::uint32_t vertices_per_strand = 0;
  std::uint32_t vertices_offset = 0;
  std::uint32_t thickness_offset = 0;
  std::uint32_t color_offset = 0;
};

TfxHeader read_header(detail::ByteReader& reader) {
  if (reader.size() < kHeaderBytes)
    reader.fail("file is truncated: a TressFX header needs " + std::to_string(kHeaderBytes) +
                " bytes, the file has " + std::to_string(reader.size()));
  TfxHeader header;
  header.version = reader.read<float>("version");
  header.strands = reader.read<std::uint32_t>("strand count");
  header.vertices_per_strand = reader.read<std::uint32_t>("vertices per strand");
  reader.seek(kOffsetsAt, "the offset table");
  header.vertices_offset = reader.read<std::uint32_t>("vertex offset");
  header.thickness_offset = reader.read<std::uint32_t>("thickness offset");
  reader.read<std::uint32_t>("strand texcoord offset");
  header.color_offset = reader.read<std::uint32_t>("colour offset");

  if (!(header.version >= 3.0f && header.version < 4.0f))
    reader.fail("not a TressFX 3 file: header version is " + std::to_string(header.version) +
                " (expected 3.x)");
  if (header.strands == 0) reader.fail("header declares no strands");
  if (header.vertices_per_strand < 2 || header.vertices_per_strand > kMaxVerticesPerStrand)
    reader.fail("header declares " + std::to_string(header.vertices_per_strand) +
                " vertices per strand (TressFX allows 2 to 64)");
  if (header.vertices_offset < kHeaderBytes)
    reader.fail("vertex data offset " + std::to_string(header.vertices_offset) +
                " points into the 296-byte header");
  return header;
}

void check_optional_offset(const detail::ByteReader& reader, std::uint32_t offset, const char* what) {
  if (offset != 0 && offset < kHeaderBytes)
    reader.fail(std::string(what) + " offset " + std::to_string(offset) + " points into the header");
}

}  // namespace

HairGroom parse_tfx(std::span<const std::byte> bytes, const std::filesystem::path& name) {
  detail::ByteReader reader(bytes, name);
  const TfxHeader header = read_header(reader);
  const std::uint64_t strands = header.strands;
  const std::uint64_t per_strand = header.vertices_per_strand;

  HairGroom groom;
  groom.name = name.stem().string();
  groom.width_kind = StrandWidth::relative;
  reader.seek(header.vertices_offset, "vertex data");
  groom.points = reader.read_array<glm::vec3>(strands * per_strand, "vertex positions");
  groom.strand_offsets.resize(strands + 1);
  for (std::uint64_t s = 0; s <= strands; ++s) groom.strand_offsets[s] = static_cast<std::uint32_t>(s * per_strand);

  check_optional_offset(reader, header.thickness_offset, "thickness");
  if (header.thickness_offset != 0) {
    reader.seek(header.thickness_offset, "strand thickness");
    groom.strand_width = reader.read_array<float>(strands, "strand thickness");
  } else {
    groom.strand_width.assign(strands, 1.0f);
  }

  groom.strand_opacity.assign(strands, kDefaultStrandOpacity);
  check_optional_offset(reader, header.color_offset, "colour");
  if (header.color_offset != 0) {
    reader.seek(header.color_offset, "vertex colours");
    const auto rgba = reader.read_array<glm::vec4>(strands * per_strand, "vertex colours");
    groom.strand_color.resize(strands);
    for (std::uint64_t s = 0; s < strands; ++s) {
      glm::vec3 sum(0.0f);
      for (std::uint64_t v = 0; v < per_strand; ++v) sum += glm::vec3(rgba[s * per_strand + v]);
      groom.strand_color[s] = sum / float(per_strand);
    }
  } else {
    groom.strand_color.assign(strands, kDefaultStrandColor);
  }

  validate_groom(groom, name);
  return groom;
}

HairGroom load_tfx(const std::filesystem::path& file) {
  return parse_tfx(detail::read_file_bytes(file, kMaxHairFileBytes), file);
}

namespace {

void pad_to(std::vector<std::byte>& out, std::size_t alignment) {
  while (out.size() % alignment != 0) out.push_back(std::byte{0});
}

}  // namespace

std::vector<std::byte> encode_tfx(const HairGroom& groom) {
  const std::size_t strands = groom.strand_count();
  if (strands == 0) throw std::invalid_argument("encode_tfx: groom has no strands");
  const std::size_t per_strand = groom.strand_size(0);
  for (std::size_t s = 0; s < strands; ++s)
    if (groom.strand_size(s) != per_strand)
      throw std::invalid_argument("encode_tfx: TressFX needs the same number of points on every strand");
  if (per_strand < 2 || per_strand > kMaxVerticesPerStrand)
    throw std::invalid_argument("encode_tfx: TressFX allows 2 to 64 points per strand");

  const bool write_thickness =
      std::any_of(groom.strand_width.begin(), groom.strand_width.end(), [](float w) { return w != 1.0f; });
  const std::size_t positions_bytes = groom.points.size() * sizeof(glm::vec3);
  const std::size_t thickness_offset = (kHeaderBytes + positions_bytes + 7) / 8 * 8;

  std::vector<std::byte> out;
  detail::append_bytes(out, 3.0f);
  detail::append_bytes(out, static_cast<std::uint32_t>(strands));
  detail::append_bytes(out, static_cast<std::uint32_t>(per_strand));
  out.resize(kOffsetsAt, std::byte{0});  // follow hairs, bothEndsImmovable, reserved1: zero
  detail::append_bytes(out, static_cast<std::uint32_t>(kHeaderBytes));
  detail::append_bytes(out, static_cast<std::uint32_t>(write_thickness ? thickness_offset : 0));
  out.resize(kHeaderBytes, std::byte{0});
  for (const glm::vec3& p : groom.points) detail::append_bytes(out, p);
  if (write_thickness) {
    pad_to(out, 8);
    for (float w : groom.strand_width) detail::append_bytes(out, w);
  }
  return out;
}

}  // namespace avsm::scene
