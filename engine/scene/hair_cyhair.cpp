// cyHair .hair (Cem Yuksel, http://www.cemyuksel.com/research/hairmodels/):
//   0 char  signature[4] = "HAIR"
//   4 uint  hair_count
//   8 uint  point_count
//  12 uint  arrays: bit 0 segments, 1 points, 2 thickness, 3 transparency, 4 colour
//  16 uint  d_segments      segments per strand when there is no segments array
//  20 float d_thickness     used when there is no thickness array
//  24 float d_transparency  used when there is no transparency array
//  28 float d_color[3]      used when there is no colour array
//  40 char  info[88]
// 128 arrays in the order above: uint16 segments[hair_count], float3 points,
//     float thickness, float transparency, float3 colour (all per point).
// A strand with n segments has n + 1 points.
#include "scene/binary_reader.h"
#include "scene/hair.h"

#include <array>
#include <cstring>
#include <numeric>

namespace avsm::scene {
namespace {

constexpr std::size_t kHeaderBytes = 128;
constexpr std::uint32_t kSegmentsBit = 1u << 0, kPointsBit = 1u << 1, kThicknessBit = 1u << 2,
                        kTransparencyBit = 1u << 3, kColorBit = 1u << 4;
constexpr std::uint32_t kKnownBits = 0x1f;

struct CyHairHeader {
  std::uint32_t hair_count = 0;
  std::uint32_t point_count = 0;
  std::uint32_t arrays = 0;
  std::uint32_t default_segments = 0;
  float default_thickness = 1.0f;
  float default_transparency = 0.0f;
  glm::vec3 default_color{0.0f};
};

CyHairHeader read_header(detail::ByteReader& reader) {
  if (reader.size() < kHeaderBytes)
    reader.fail("file is truncated: a cyHair header needs 128 bytes, the file has " +
                std::to_string(reader.size()));
  const auto signature = reader.read<std::array<char, 4>>("signature");
  if (std::memcmp(signature.data(), "HAIR", 4) != 0) reader.fail("not a cyHair file: signature is not 'HAIR'");
  CyHairHeader header;
  header.hair_count = reader.read<std::uint32_t>("hair count");
  header.point_count = reader.read<std::uint32_t>("point count");
  header.arrays = reader.read<std::uint32_t>("array flags");
  header.default_segments = reader.read<std::uint32_t>("default segments");
  header.default_thickness = reader.read<float>("default thickness");
  header.default_transparency = reader.read<float>("default transparency");
  header.default_color = reader.read<glm::vec3>("default colour");
  reader.seek(kHeaderBytes, "array data");

  if ((header.arrays & ~kKnownBits) != 0)
    reader.fail("unknown array flags " + std::to_string(header.arrays) + " (cyHair defines bits 0 to 4)");
  if ((header.arrays & kPointsBit) == 0) reader.fail("header says the file has no point array");
  if (header.hair_count == 0) reader.fail("header declares no strands");
  return header;
}

// Strand offsets from the segments array, or from the default segment count.
std::vector<std::uint32_t> read_strand_offsets(detail::ByteReader& reader, const CyHairHeader& header) {
  // Bound both counts by the file size before allocating anything per strand:
  // every strand has at least one point of 12 bytes.
  if (header.point_count > reader.remaining() / sizeof(glm::vec3))
    reader.fail("file is truncated: the header declares " + std::to_string(header.point_count) +
                " points but only " + std::to_string(reader.remaining()) + " bytes follow it");
  if (header.hair_count > header.point_count)
    reader.fail("header declares " + std::to_string(header.hair_count) + " strands but only " +
                std::to_string(header.point_count) + " points");
  std::vector<std::uint16_t> segments;
  if (header.arrays & kSegmentsBit) {
    segments = reader.read_array<std::uint16_t>(header.hair_count, "segments array");
  } else if (header.default_segments > 0xffff) {
    reader.fail("default segment count " + std::to_string(header.default_segments) + " is above 65535");
  }
  std::vector<std::uint32_t> offsets(std::size_t(header.hair_count) + 1, 0);
  std::uint64_t total = 0;
  for (std::size_t s = 0; s < header.hair_count; ++s) {
    total += (segments.empty() ? header.default_segments : segments[s]) + 1u;
    if (total > header.point_count)
      reader.fail("segments describe more points than the " + std::to_string(header.point_count) +
                  " the header declares");
    offsets[s + 1] = static_cast<std::uint32_t>(total);
  }
  if (total != header.point_count)
    reader.fail("segments describe " + std::to_string(total) + " points but the header declares " +
                std::to_string(header.point_count));
  return offsets;
}

template <class T>
std::vector<T> average_per_strand(const std::vector<T>& per_point, const std::vector<std::uint32_t>& offsets) {
  std::vector<T> result(offsets.size() - 1);
  for (std::size_t s = 0; s + 1 < offsets.size(); ++s) {
    T sum = std::accumulate(per_point.begin() + offsets[s], per_point.begin() + offsets[s + 1], T(0));
    result[s] = sum / float(offsets[s + 1] - offsets[s]);
  }
  return result;
}

}  // namespace

HairGroom parse_cyhair(std::span<const std::byte> bytes, const std::filesystem::path& name) {
  detail::ByteReader reader(bytes, name);
  const CyHairHeader header = read_header(reader);
  const std::size_t strands = header.hair_count;

  HairGroom groom;
  groom.name = name.stem().string();
  groom.width_kind = StrandWidth::absolute;
  groom.strand_offsets = read_strand_offsets(reader, header);
  groom.points = reader.read_array<glm::vec3>(header.point_count, "point array");

  if (header.arrays & kThicknessBit)
    groom.strand_width = average_per_strand(reader.read_array<float>(header.point_count, "thickness array"),
                                            groom.strand_offsets);
  else
    groom.strand_width.assign(strands, header.default_thickness);

  if (header.arrays & kTransparencyBit)
    groom.strand_opacity = average_per_strand(
        reader.read_array<float>(header.point_count, "transparency array"), groom.strand_offsets);
  else
    groom.strand_opacity.assign(strands, header.default_transparency);
  for (float& opacity : groom.strand_opacity) opacity = 1.0f - opacity;  // stored as transparency

  if (header.arrays & kColorBit)
    groom.strand_color = average_per_strand(reader.read_array<glm::vec3>(header.point_count, "colour array"),
                                            groom.strand_offsets);
  else
    groom.strand_color.assign(strands, header.default_color);

  validate_groom(groom, name);
  return groom;
}

HairGroom load_cyhair(const std::filesystem::path& file) {
  return parse_cyhair(detail::read_file_bytes(file, kMaxHairFileBytes), file);
}

std::vector<std::byte> encode_cyhair(const HairGroom& groom) {
  const std::size_t strands = groom.strand_count();
  if (strands == 0) throw std::invalid_argument("encode_cyhair: groom has no strands");
  for (std::size_t s = 0; s < strands; ++s)
    if (groom.strand_size(s) < 1 || groom.strand_size(s) > 0x10000)
      throw std::invalid_argument("encode_cyhair: cyHair allows 1 to 65536 points per strand");

  std::vector<std::byte> out;
  detail::append_bytes(out, std::array<char, 4>{'H', 'A', 'I', 'R'});
  detail::append_bytes(out, static_cast<std::uint32_t>(strands));
  detail::append_bytes(out, static_cast<std::uint32_t>(groom.points.size()));
  detail::append_bytes(out, kKnownBits);
  detail::append_bytes(out, std::uint32_t{0});
  detail::append_bytes(out, 1.0f);                // defaults unused: every array is present
  detail::append_bytes(out, 0.0f);
  detail::append_bytes(out, glm::vec3(0.0f));
  std::array<char, 88> info{};
  std::strncpy(info.data(), "written by avsm_scene encode_cyhair", info.size() - 1);
  detail::append_bytes(out, info);

  for (std::size_t s = 0; s < strands; ++s) detail::append_bytes(out, static_cast<std::uint16_t>(groom.strand_size(s) - 1));
  for (const glm::vec3& p : groom.points) detail::append_bytes(out, p);
  auto per_point = [&](auto value_of_strand) {
    for (std::size_t s = 0; s < strands; ++s)
      for (std::size_t i = 0; i < groom.strand_size(s); ++i) detail::append_bytes(out, value_of_strand(s));
  };
  per_point([&](std::size_t s) { return groom.strand_width[s]; });
  per_point([&](std::size_t s) { return 1.0f - groom.strand_opacity[s]; });
  per_point([&](std::size_t s) { return groom.strand_color[s]; });
  return out;
}

}  // namespace avsm::scene
