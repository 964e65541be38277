// TressFX .tfx, two header layouts chosen by the leading float version. All
// offsets are bytes from the start of the file; arrays may lie anywhere after
// the header, in any order.
//
// TressFX 3 ("TressFXFileObject", AMD TressFX 3.x TressFXFileFormat.h):
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
// 296  end of header
//
// TressFX 4 ("TressFXTFXFileHeader", AMD TressFX 4.x TressFXFileFormat.h):
//   0  float version                  (4.x)
//   4  uint  numHairStrands
//   8  uint  numVerticesPerStrand     (same for all strands)
//  12  uint  offsetVertexPosition     float4 per vertex: xyz, w = inverse mass
//                                     (0 = pinned root; simulation only, ignored)
//  16  uint  offsetStrandUV           float2 per strand, 0 = absent (checked, not kept)
//  20  uint  offsetVertexUV           float2 per vertex, 0 = absent (checked, not kept)
//  24  uint  offsetStrandThickness    float per strand, 0 = absent
//  28  uint  offsetVertexColor        float4 per vertex, 0 = absent
//  32  uint  reserved[32]
// 160  end of header
//
// TressFX 4's texture coordinates are checked to lie inside the file but not
// kept: a HairGroom has one colour per strand and no texture to look them up in.
#include "scene/binary_reader.h"
#include "scene/hair.h"

#include <algorithm>
#include <cmath>
#include <cstring>

namespace avsm::scene {
namespace {

constexpr std::size_t kTfx3HeaderBytes = 296;
constexpr std::size_t kTfx3OffsetsAt = 144;
constexpr std::size_t kTfx4HeaderBytes = 160;
constexpr std::uint32_t kMaxVerticesPerStrand = 64;

// What both header versions say, in one shape.
struct TfxHeader {
  int major_version = 0;
  std::size_t header_bytes = 0;
  std::uint32_t strands = 0;
  std::uint32_t vertices_per_strand = 0;
  std::uint32_t positions_offset = 0;
  std::size_t position_bytes = 0;  // float3 (3.x) or float4 (4.x)
  std::uint32_t thickness_offset = 0;
  std::uint32_t color_offset = 0;
  std::uint32_t strand_uv_offset = 0;  // 4.x only: checked, not kept
  std::uint32_t vertex_uv_offset = 0;  // 4.x only: checked, not kept
};

int major_version_of(float version) {
  if (version >= 3.0f && version < 4.0f) return 3;
  if (version >= 4.0f && version < 5.0f) return 4;
  return 0;
}

void require_header_bytes(const detail::ByteReader& reader, int major_version, std::size_t header_bytes) {
  if (reader.size() < header_bytes)
    reader.fail("file is truncated: a TressFX " + std::to_string(major_version) + " header needs " +
                std::to_string(header_bytes) + " bytes, the file has " + std::to_string(reader.size()));
}

TfxHeader read_tfx3_header(detail::ByteReader& reader) {
  require_header_bytes(reader, 3, kTfx3HeaderBytes);
  TfxHeader header{.major_version = 3, .header_bytes = kTfx3HeaderBytes, .position_bytes = sizeof(glm::vec3)};
  header.strands = reader.read<std::uint32_t>("strand count");
  header.vertices_per_strand = reader.read<std::uint32_t>("vertices per strand");
  reader.seek(kTfx3OffsetsAt, "the offset table");
  header.positions_offset = reader.read<std::uint32_t>("vertex offset");
  header.thickness_offset = reader.read<std::uint32_t>("thickness offset");
  reader.read<std::uint32_t>("strand texcoord offset");
  header.color_offset = reader.read<std::uint32_t>("colour offset");
  return header;
}

TfxHeader read_tfx4_header(detail::ByteReader& reader) {
  require_header_bytes(reader, 4, kTfx4HeaderBytes);
  TfxHeader header{.major_version = 4, .header_bytes = kTfx4HeaderBytes, .position_bytes = sizeof(glm::vec4)};
  header.strands = reader.read<std::uint32_t>("strand count");
  header.vertices_per_strand = reader.read<std::uint32_t>("vertices per strand");
  header.positions_offset = reader.read<std::uint32_t>("vertex offset");
  header.strand_uv_offset = reader.read<std::uint32_t>("strand texcoord offset");
  header.vertex_uv_offset = reader.read<std::uint32_t>("vertex texcoord offset");
  header.thickness_offset = reader.read<std::uint32_t>("thickness offset");
  header.color_offset = reader.read<std::uint32_t>("colour offset");
  return header;
}

void check_counts(const detail::ByteReader& reader, const TfxHeader& header) {
  if (header.strands == 0) reader.fail("header declares no strands");
  if (header.vertices_per_strand < 2 || header.vertices_per_strand > kMaxVerticesPerStrand)
    reader.fail("header declares " + std::to_string(header.vertices_per_strand) +
                " vertices per strand (TressFX allows 2 to 64)");
  if (header.positions_offset < header.header_bytes)
    reader.fail("vertex data offset " + std::to_string(header.positions_offset) + " points into the " +
                std::to_string(header.header_bytes) + "-byte header");
}

// An optional array (offset 0 = absent) must start after the header.
void check_optional_offset(const detail::ByteReader& reader, const TfxHeader& header, std::uint32_t offset,
                           const char* what) {
  if (offset != 0 && offset < header.header_bytes)
    reader.fail(std::string(what) + " offset " + std::to_string(offset) + " points into the header");
}

TfxHeader read_header(detail::ByteReader& reader) {
  if (reader.size() < sizeof(float))
    reader.fail("file is truncated: a TressFX header needs at least " + std::to_string(kTfx4HeaderBytes) +
                " bytes, the file has " + std::to_string(reader.size()));
  const float version = reader.read<float>("version");
  const int major = major_version_of(version);
  if (major == 0)
    reader.fail("not a TressFX 3 or 4 file: header version is " + std::to_string(version) + " (expected 3.x or 4.x)");
  const TfxHeader header = major == 3 ? read_tfx3_header(reader) : read_tfx4_header(reader);
  check_counts(reader, header);
  check_optional_offset(reader, header, header.thickness_offset, "thickness");
  check_optional_offset(reader, header, header.color_offset, "colour");
  check_optional_offset(reader, header, header.strand_uv_offset, "strand texcoord");
  check_optional_offset(reader, header, header.vertex_uv_offset, "vertex texcoord");
  return header;
}

std::vector<glm::vec3> read_positions(detail::ByteReader& reader, const TfxHeader& header) {
  const std::uint64_t count = std::uint64_t(header.strands) * header.vertices_per_strand;
  reader.seek(header.positions_offset, "vertex data");
  if (header.position_bytes == sizeof(glm::vec3)) return reader.read_array<glm::vec3>(count, "vertex positions");
  const auto xyzw = reader.read_array<glm::vec4>(count, "vertex positions");
  std::vector<glm::vec3> xyz(xyzw.size());
  std::transform(xyzw.begin(), xyzw.end(), xyz.begin(), [](const glm::vec4& p) { return glm::vec3(p); });
  return xyz;
}

std::vector<glm::vec3> average_colors_per_strand(const std::vector<glm::vec4>& rgba, std::size_t per_strand) {
  std::vector<glm::vec3> colors(rgba.size() / per_strand);
  for (std::size_t s = 0; s < colors.size(); ++s) {
    glm::vec3 sum(0.0f);
    for (std::size_t v = 0; v < per_strand; ++v) sum += glm::vec3(rgba[s * per_strand + v]);
    colors[s] = sum / float(per_strand);
  }
  return colors;
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
  groom.points = read_positions(reader, header);
  groom.strand_offsets.resize(strands + 1);
  for (std::uint64_t s = 0; s <= strands; ++s) groom.strand_offsets[s] = static_cast<std::uint32_t>(s * per_strand);

  if (header.thickness_offset != 0) {
    reader.seek(header.thickness_offset, "strand thickness");
    groom.strand_width = reader.read_array<float>(strands, "strand thickness");
  } else {
    groom.strand_width.assign(strands, 1.0f);
  }

  groom.strand_opacity.assign(strands, kDefaultStrandOpacity);
  if (header.color_offset != 0) {
    reader.seek(header.color_offset, "vertex colours");
    groom.strand_color =
        average_colors_per_strand(reader.read_array<glm::vec4>(strands * per_strand, "vertex colours"), per_strand);
  } else {
    groom.strand_color.assign(strands, kDefaultStrandColor);
  }

  if (header.strand_uv_offset != 0) {
    reader.seek(header.strand_uv_offset, "strand texcoords");
    reader.skip_array(strands, sizeof(glm::vec2), "strand texcoords");
  }
  if (header.vertex_uv_offset != 0) {
    reader.seek(header.vertex_uv_offset, "vertex texcoords");
    reader.skip_array(strands * per_strand, sizeof(glm::vec2), "vertex texcoords");
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

// The offsets an encoded file gets: positions right after the header, the
// thickness factors (if written) after them on an 8-byte boundary.
struct TfxEncodedLayout {
  std::uint32_t positions_offset = 0;
  std::uint32_t thickness_offset = 0;  // 0 = not written
};

TfxEncodedLayout encoded_layout(const HairGroom& groom, std::size_t header_bytes, std::size_t position_bytes) {
  const bool write_thickness =
      std::any_of(groom.strand_width.begin(), groom.strand_width.end(), [](float w) { return w != 1.0f; });
  const std::size_t positions_end = header_bytes + groom.points.size() * position_bytes;
  return {static_cast<std::uint32_t>(header_bytes),
          write_thickness ? static_cast<std::uint32_t>((positions_end + 7) / 8 * 8) : 0u};
}

void check_encodable(const HairGroom& groom) {
  const std::size_t strands = groom.strand_count();
  if (strands == 0) throw std::invalid_argument("encode_tfx: groom has no strands");
  const std::size_t per_strand = groom.strand_size(0);
  for (std::size_t s = 0; s < strands; ++s)
    if (groom.strand_size(s) != per_strand)
      throw std::invalid_argument("encode_tfx: TressFX needs the same number of points on every strand");
  if (per_strand < 2 || per_strand > kMaxVerticesPerStrand)
    throw std::invalid_argument("encode_tfx: TressFX allows 2 to 64 points per strand");
}

void append_tfx3_header(std::vector<std::byte>& out, const HairGroom& groom, const TfxEncodedLayout& layout) {
  detail::append_bytes(out, 3.0f);
  detail::append_bytes(out, static_cast<std::uint32_t>(groom.strand_count()));
  detail::append_bytes(out, static_cast<std::uint32_t>(groom.strand_size(0)));
  out.resize(kTfx3OffsetsAt, std::byte{0});  // follow hairs, bothEndsImmovable, reserved1: zero
  detail::append_bytes(out, layout.positions_offset);
  detail::append_bytes(out, layout.thickness_offset);
  out.resize(kTfx3HeaderBytes, std::byte{0});
}

void append_tfx4_header(std::vector<std::byte>& out, const HairGroom& groom, const TfxEncodedLayout& layout) {
  detail::append_bytes(out, 4.0f);
  detail::append_bytes(out, static_cast<std::uint32_t>(groom.strand_count()));
  detail::append_bytes(out, static_cast<std::uint32_t>(groom.strand_size(0)));
  detail::append_bytes(out, layout.positions_offset);
  detail::append_bytes(out, std::uint32_t{0});  // strand UVs: none
  detail::append_bytes(out, std::uint32_t{0});  // vertex UVs: none
  detail::append_bytes(out, layout.thickness_offset);
  detail::append_bytes(out, std::uint32_t{0});  // vertex colours: none
  out.resize(kTfx4HeaderBytes, std::byte{0});   // reserved: zero
}

}  // namespace

std::vector<std::byte> encode_tfx(const HairGroom& groom, TfxVersion version) {
  check_encodable(groom);
  const bool v4 = version == TfxVersion::v4;
  const TfxEncodedLayout layout = encoded_layout(groom, v4 ? kTfx4HeaderBytes : kTfx3HeaderBytes,
                                                 v4 ? sizeof(glm::vec4) : sizeof(glm::vec3));
  std::vector<std::byte> out;
  if (v4) {
    append_tfx4_header(out, groom, layout);
    // w is TressFX 4's inverse mass: 0 pins a strand's root, 1 lets the rest move.
    for (std::size_t s = 0; s < groom.strand_count(); ++s)
      for (std::uint32_t i = groom.strand_offsets[s]; i < groom.strand_offsets[s + 1]; ++i)
        detail::append_bytes(out, glm::vec4(groom.points[i], i == groom.strand_offsets[s] ? 0.0f : 1.0f));
  } else {
    append_tfx3_header(out, groom, layout);
    for (const glm::vec3& p : groom.points) detail::append_bytes(out, p);
  }
  if (layout.thickness_offset != 0) {
    pad_to(out, 8);
    for (float w : groom.strand_width) detail::append_bytes(out, w);
  }
  return out;
}

}  // namespace avsm::scene
