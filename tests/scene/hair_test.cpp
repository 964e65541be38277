// TressFX and cyHair: the real ponytail, round trips, and malformed files.
#include "support.h"

#include "scene/hair.h"

#include <cmath>
#include <cstring>
#include <limits>

namespace avsm::scene {
namespace hair_test {  // one per file: test targets are unity builds
namespace {

using testing::TempDir;
using testing::load_error_of;
using testing::put;

const char* const kPonytailParts[] = {"back.tfx", "front_top.tfx", "side.tfx", "tail.tfx"};

// A small groom with varied strand lengths and attributes.
HairGroom sample_groom(bool equal_lengths) {
  HairGroom groom;
  groom.strand_offsets = {0};
  for (int s = 0; s < 5; ++s) {
    const int points = equal_lengths ? 4 : 2 + s;
    for (int p = 0; p < points; ++p) groom.points.emplace_back(0.1f * s, -0.25f * p, 0.01f * s * p);
    groom.strand_offsets.push_back(std::uint32_t(groom.points.size()));
    groom.strand_width.push_back(0.5f + 0.25f * s);
    groom.strand_opacity.push_back(0.2f * s);
    groom.strand_color.emplace_back(0.1f * s, 0.5f, 1.0f);
  }
  groom.width_kind = StrandWidth::absolute;
  return groom;
}

TEST(Tfx, PonytailPartsHaveTheDocumentedCounts) {
  std::size_t strands = 0, points = 0;
  const std::size_t expected_strands[] = {517, 876, 3066, 255};  // read from each header
  for (int part = 0; part < 4; ++part) {
    const auto file = testing::shared_content(std::string("ponytail/") + kPonytailParts[part]);
    AVSM_REQUIRE_FILE(file);
    const HairGroom groom = load_tfx(file);
    EXPECT_EQ(groom.strand_count(), expected_strands[part]) << file;
    for (std::size_t s = 0; s < groom.strand_count(); ++s) ASSERT_EQ(groom.strand_size(s), 16u);
    EXPECT_EQ(groom.width_kind, StrandWidth::relative);
    strands += groom.strand_count();
    points += groom.points.size();
  }
  EXPECT_EQ(strands, 4714u);  // shared/content/README.md
  EXPECT_EQ(points, 75424u);
}

TEST(CyHair, PonytailHasTheSamePositionsAsTheTfxParts) {
  const auto file = testing::shared_content("ponytail/ponytail_all.hair");
  AVSM_REQUIRE_FILE(file);
  const HairGroom all = load_cyhair(file);
  ASSERT_EQ(all.strand_count(), 4714u);
  ASSERT_EQ(all.points.size(), 75424u);
  EXPECT_EQ(all.width_kind, StrandWidth::absolute);
  EXPECT_FLOAT_EQ(all.strand_width[0], 1.0f);    // header default thickness
  EXPECT_FLOAT_EQ(all.strand_opacity[0], 1.0f);  // default transparency 0
  EXPECT_NEAR(all.bounds.size().y, 126.8f, 0.5f);  // "about 125 units tall"

  // The .hair concatenates back, front_top, side, tail with positions unchanged.
  std::size_t point = 0, strand = 0;
  for (const char* part : kPonytailParts) {
    const auto part_file = testing::shared_content(std::string("ponytail/") + part);
    AVSM_REQUIRE_FILE(part_file);
    const HairGroom tfx = load_tfx(part_file);
    for (std::size_t s = 0; s < tfx.strand_count(); ++s, ++strand)
      ASSERT_EQ(all.strand_size(strand), tfx.strand_size(s)) << part << " strand " << s;
    for (const glm::vec3& p : tfx.points) {
      ASSERT_EQ(all.points[point], p) << part << " point " << point;
      ++point;
    }
  }
  EXPECT_EQ(point, all.points.size());
}

TEST(Tfx, RoundTripKeepsPositionsAndThickness) {
  HairGroom groom = sample_groom(true);
  groom.width_kind = StrandWidth::relative;
  TempDir dir;
  testing::write_bytes(dir / "g.tfx", encode_tfx(groom));
  const HairGroom loaded = load_tfx(dir / "g.tfx");
  EXPECT_EQ(loaded.points, groom.points);
  EXPECT_EQ(loaded.strand_offsets, groom.strand_offsets);
  EXPECT_EQ(loaded.strand_width, groom.strand_width);
  EXPECT_EQ(loaded.strand_opacity, std::vector<float>(5, kDefaultStrandOpacity));
  EXPECT_EQ(loaded.name, "g");
}

// Appends `values` on an 8-byte boundary (TressFX aligns its arrays so) and
// returns the offset they start at.
template <class T>
std::uint32_t append_array(std::vector<std::byte>& bytes, const std::vector<T>& values) {
  while (bytes.size() % 8 != 0) bytes.push_back(std::byte{0});
  const auto offset = static_cast<std::uint32_t>(bytes.size());
  bytes.resize(offset + values.size() * sizeof(T));
  std::memcpy(bytes.data() + offset, values.data(), values.size() * sizeof(T));
  return offset;
}

// TressFX 4 header fields (TressFXTFXFileHeader).
constexpr std::size_t kTfx4Strands = 4, kTfx4VerticesPerStrand = 8, kTfx4Positions = 12, kTfx4StrandUv = 16,
                      kTfx4VertexUv = 20, kTfx4Thickness = 24, kTfx4Color = 28;

TEST(Tfx4, SintelHasTheDocumentedCountsAndBounds) {
  const auto file = testing::shared_content("sintel/sintel_hair.tfx");
  AVSM_REQUIRE_FILE(file);
  const HairGroom groom = load_tfx(file);
  ASSERT_EQ(groom.strand_count(), 228u);  // shared/content/README.md
  for (std::size_t s = 0; s < groom.strand_count(); ++s) ASSERT_EQ(groom.strand_size(s), 32u);
  EXPECT_EQ(groom.points.size(), 7296u);
  // The first float4 of the file (offset 160), read with Python's struct: xyz kept, w (0) dropped.
  EXPECT_EQ(groom.points[0], glm::vec3(-8.315415382385254f, 34.9295539855957f, -2.681877851486206f));
  // Bounds of all 7,296 xyz triples, also from Python: about 20 x 27 x 25 units.
  EXPECT_NEAR(groom.bounds.min.x, -10.6175f, 1e-3f);
  EXPECT_NEAR(groom.bounds.min.y, 20.7159f, 1e-3f);
  EXPECT_NEAR(groom.bounds.min.z, -12.9518f, 1e-3f);
  EXPECT_NEAR(groom.bounds.max.x, 9.8269f, 1e-3f);
  EXPECT_NEAR(groom.bounds.max.y, 47.6863f, 1e-3f);
  EXPECT_NEAR(groom.bounds.max.z, 11.6560f, 1e-3f);
  // The file has no thickness or colour arrays: the same defaults as TressFX 3.
  EXPECT_EQ(groom.width_kind, StrandWidth::relative);
  EXPECT_EQ(groom.strand_width, std::vector<float>(228, 1.0f));
  EXPECT_EQ(groom.strand_color, std::vector<glm::vec3>(228, kDefaultStrandColor));
  EXPECT_EQ(groom.strand_opacity, std::vector<float>(228, kDefaultStrandOpacity));
}

TEST(Tfx4, RoundTripKeepsPositionsAndThickness) {
  const HairGroom groom = sample_groom(true);
  const auto bytes = encode_tfx(groom, TfxVersion::v4);
  EXPECT_EQ(bytes.size(), 160u + 20 * 16 + 5 * 4);
  const HairGroom loaded = parse_tfx(bytes, "g.tfx");
  EXPECT_EQ(loaded.points, groom.points);
  EXPECT_EQ(loaded.strand_offsets, groom.strand_offsets);
  EXPECT_EQ(loaded.strand_width, groom.strand_width);
  EXPECT_EQ(loaded.strand_color, std::vector<glm::vec3>(5, kDefaultStrandColor));
}

TEST(Tfx4, OffsetsAreHonouredNotAssumedContiguous) {
  const HairGroom groom = sample_groom(true);
  const auto plain = encode_tfx(groom, TfxVersion::v4);
  // Header, 24 bytes of NaNs (read as positions only by a loader that ignores
  // offsetVertexPosition), the thickness factors, then the positions.
  std::vector<std::byte> bytes(plain.begin(), plain.begin() + 160);
  append_array(bytes, std::vector<float>(6, std::numeric_limits<float>::quiet_NaN()));
  const std::uint32_t thickness = append_array(bytes, groom.strand_width);
  const std::uint32_t positions = append_array(bytes, std::vector<std::byte>(plain.begin() + 160, plain.begin() + 160 + 320));
  put(bytes, kTfx4Positions, positions);
  put(bytes, kTfx4Thickness, thickness);
  ASSERT_GT(positions, thickness);
  const HairGroom loaded = parse_tfx(bytes, "reordered.tfx");
  EXPECT_EQ(loaded.points, groom.points);
  EXPECT_EQ(loaded.strand_width, groom.strand_width);
}

TEST(Tfx4, UvsAreCheckedAndColoursAveragedPerStrand) {
  auto bytes = encode_tfx(sample_groom(true), TfxVersion::v4);
  put(bytes, kTfx4StrandUv, append_array(bytes, std::vector<glm::vec2>(5, glm::vec2(0.25f, 0.5f))));
  put(bytes, kTfx4VertexUv, append_array(bytes, std::vector<glm::vec2>(20, glm::vec2(0.75f))));
  std::vector<glm::vec4> rgba(20, glm::vec4(0.2f, 0.4f, 0.6f, 1.0f));
  for (int v = 0; v < 4; ++v) rgba[v] = glm::vec4(0.1f * v, 0.0f, 1.0f, 1.0f);  // strand 0: red 0, .1, .2, .3
  put(bytes, kTfx4Color, append_array(bytes, rgba));
  const HairGroom loaded = parse_tfx(bytes, "uv.tfx");
  EXPECT_NEAR(loaded.strand_color[0].r, 0.15f, 1e-6f);
  EXPECT_EQ(loaded.strand_color[0].b, 1.0f);
  EXPECT_EQ(loaded.strand_color[4], glm::vec3(0.2f, 0.4f, 0.6f));
  EXPECT_EQ(loaded.points, sample_groom(true).points);
}

TEST(Tfx, EncodeRefusesUnequalStrands) {
  EXPECT_THROW(encode_tfx(sample_groom(false)), std::invalid_argument);
}

TEST(CyHair, RoundTripKeepsEverything) {
  const HairGroom groom = sample_groom(false);
  const HairGroom loaded = parse_cyhair(encode_cyhair(groom), "mem.hair");
  EXPECT_EQ(loaded.points, groom.points);
  EXPECT_EQ(loaded.strand_offsets, groom.strand_offsets);
  EXPECT_EQ(loaded.strand_width, groom.strand_width);
  for (std::size_t s = 0; s < groom.strand_count(); ++s) {
    EXPECT_NEAR(loaded.strand_opacity[s], groom.strand_opacity[s], 1e-6f);
    EXPECT_EQ(loaded.strand_color[s], groom.strand_color[s]);
  }
  EXPECT_EQ(loaded.bounds.min, glm::vec3(0.0f, -1.25f, 0.0f));  // longest strand: 6 points
}

TEST(CyHair, PerPointValuesAreAveragedPerStrand) {
  auto bytes = encode_cyhair(sample_groom(true));  // 5 strands x 4 points, all arrays present
  const std::size_t thickness_at = 128 + 5 * 2 + 20 * 12;
  for (int p = 0; p < 4; ++p) put(bytes, thickness_at + 4 * p, float(p));  // strand 0: 0, 1, 2, 3
  EXPECT_FLOAT_EQ(parse_cyhair(bytes, "x.hair").strand_width[0], 1.5f);
}

TEST(CyHair, WithoutSegmentsArrayUsesTheDefaultSegmentCount) {
  auto full = encode_cyhair(sample_groom(true));
  // Rebuild: header with arrays = points only, d_segments = 3, no segments array.
  std::vector<std::byte> bytes(full.begin(), full.begin() + 128);
  put(bytes, 12, std::uint32_t{2});
  put(bytes, 16, std::uint32_t{3});
  put(bytes, 20, 0.25f);  // default thickness
  put(bytes, 24, 0.75f);  // default transparency
  bytes.insert(bytes.end(), full.begin() + 128 + 10, full.begin() + 128 + 10 + 20 * 12);
  const HairGroom groom = parse_cyhair(bytes, "x.hair");
  ASSERT_EQ(groom.strand_count(), 5u);
  EXPECT_EQ(groom.strand_size(4), 4u);
  EXPECT_FLOAT_EQ(groom.strand_width[2], 0.25f);
  EXPECT_FLOAT_EQ(groom.strand_opacity[2], 0.25f);
}

TEST(Hair, TransformScalesAbsoluteWidthsOnly) {
  HairGroom absolute = sample_groom(true);
  transform_groom(absolute, glm::mat4(glm::vec4(2, 0, 0, 0), glm::vec4(0, 2, 0, 0), glm::vec4(0, 0, 2, 0), glm::vec4(1, 0, 0, 1)));
  EXPECT_FLOAT_EQ(absolute.strand_width[0], 1.0f);
  EXPECT_EQ(absolute.points[1], glm::vec3(1.0f, -0.5f, 0.0f));
  HairGroom relative = sample_groom(true);
  relative.width_kind = StrandWidth::relative;
  transform_groom(relative, glm::mat4(2.0f));
  EXPECT_FLOAT_EQ(relative.strand_width[0], 0.5f);
}

// ---- malformed files: every one a LoadError naming the file and the problem ----

class HairErrors : public ::testing::Test {
 protected:
  std::string tfx_error(const std::vector<std::byte>& bytes) {
    testing::write_bytes(dir_ / "bad.tfx", bytes);
    return load_error_of([&] { load_tfx(dir_ / "bad.tfx"); });
  }
  std::string hair_error(const std::vector<std::byte>& bytes) {
    testing::write_bytes(dir_ / "bad.hair", bytes);
    return load_error_of([&] { load_cyhair(dir_ / "bad.hair"); });
  }
  std::vector<std::byte> good_tfx() { return encode_tfx(sample_groom(true)); }
  // 5 strands x 4 points: header 160, positions 160..480, thickness 480..500.
  std::vector<std::byte> good_tfx4() { return encode_tfx(sample_groom(true), TfxVersion::v4); }
  std::vector<std::byte> good_hair() { return encode_cyhair(sample_groom(false)); }
  TempDir dir_;
};

TEST_F(HairErrors, TfxTruncatedHeader) {
  auto bytes = good_tfx();
  bytes.resize(100);
  EXPECT_THAT(tfx_error(bytes), AllOf(HasSubstr("bad.tfx: "), HasSubstr("truncated"), HasSubstr("296 bytes")));
}

TEST_F(HairErrors, TfxTruncatedPositions) {
  auto bytes = good_tfx();
  bytes.resize(296 + 12 * 10);  // 10 of 20 points
  EXPECT_THAT(tfx_error(bytes), AllOf(HasSubstr("bad.tfx: file is truncated: vertex positions needs 20 x 12 bytes at byte 296"),
                                      HasSubstr("only 120 bytes remain")));
}

TEST_F(HairErrors, TfxVersionOtherThan3Or4) {
  auto bytes = good_tfx();
  put(bytes, 0, 5.0f);
  EXPECT_THAT(tfx_error(bytes),
              HasSubstr("bad.tfx: not a TressFX 3 or 4 file: header version is 5.000000 (expected 3.x or 4.x)"));
  put(bytes, 0, 2.0f);
  EXPECT_THAT(tfx_error(bytes), HasSubstr("header version is 2.000000"));
  put(bytes, 0, std::numeric_limits<float>::quiet_NaN());
  EXPECT_THAT(tfx_error(bytes), HasSubstr("not a TressFX 3 or 4 file"));
  EXPECT_THAT(tfx_error({bytes.begin(), bytes.begin() + 3}),
              HasSubstr("file is truncated: a TressFX header needs at least 160 bytes, the file has 3"));
}

TEST_F(HairErrors, Tfx3HeaderReadAsTfx4IsAClearError) {
  // A TressFX 3 file whose version says 4: its 3.x offset table is not where 4.x looks.
  auto bytes = good_tfx();
  put(bytes, 0, 4.0f);
  EXPECT_THAT(tfx_error(bytes), HasSubstr("bad.tfx: vertex data offset 0 points into the 160-byte header"));
}

TEST_F(HairErrors, TfxHugeCountsAreBoundedByTheFileSize) {
  auto bytes = good_tfx();
  put(bytes, 4, std::uint32_t{0xffffffff});  // strands: would be 4 G x 4 points
  EXPECT_THAT(tfx_error(bytes), HasSubstr("file is truncated: vertex positions needs"));
}

TEST_F(HairErrors, TfxVerticesPerStrandOutOfRange) {
  auto bytes = good_tfx();
  put(bytes, 8, std::uint32_t{65});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("65 vertices per strand (TressFX allows 2 to 64)"));
  put(bytes, 8, std::uint32_t{1});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("1 vertices per strand"));
}

TEST_F(HairErrors, TfxNoStrands) {
  auto bytes = good_tfx();
  put(bytes, 4, std::uint32_t{0});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("declares no strands"));
}

TEST_F(HairErrors, TfxOffsetsIntoTheHeaderOrPastTheEnd) {
  auto bytes = good_tfx();
  put(bytes, 144, std::uint32_t{8});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("points into the 296-byte header"));
  bytes = good_tfx();
  put(bytes, 148, std::uint32_t(bytes.size() + 100));  // thickness beyond the end
  EXPECT_THAT(tfx_error(bytes), HasSubstr("past the end of the file"));
}

TEST_F(HairErrors, TfxNanPosition) {
  auto bytes = good_tfx();
  put(bytes, 296 + 12 * 5 + 4, std::numeric_limits<float>::quiet_NaN());
  EXPECT_THAT(tfx_error(bytes), AllOf(HasSubstr("point 5 (strand 1) is not finite"), HasSubstr("nan")));
}

TEST_F(HairErrors, Tfx4Truncated) {
  auto bytes = good_tfx4();
  EXPECT_THAT(tfx_error({bytes.begin(), bytes.begin() + 100}),
              HasSubstr("bad.tfx: file is truncated: a TressFX 4 header needs 160 bytes, the file has 100"));
  bytes.resize(160 + 16 * 10);  // 10 of 20 float4 positions
  EXPECT_THAT(tfx_error(bytes), AllOf(HasSubstr("bad.tfx: file is truncated: vertex positions needs 20 x 16 bytes at byte 160"),
                                      HasSubstr("only 160 bytes remain")));
  bytes = good_tfx4();
  bytes.resize(bytes.size() - 1);  // the last thickness factor
  EXPECT_THAT(tfx_error(bytes), HasSubstr("file is truncated: strand thickness needs 5 x 4 bytes"));
}

TEST_F(HairErrors, Tfx4NoStrandsAndBadVertexCounts) {
  auto bytes = good_tfx4();
  put(bytes, kTfx4Strands, std::uint32_t{0});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("bad.tfx: header declares no strands"));
  bytes = good_tfx4();
  put(bytes, kTfx4VerticesPerStrand, std::uint32_t{1});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("header declares 1 vertices per strand (TressFX allows 2 to 64)"));
  put(bytes, kTfx4VerticesPerStrand, std::uint32_t{0xffffffff});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("header declares 4294967295 vertices per strand"));
}

TEST_F(HairErrors, Tfx4HugeCountsAreBoundedByTheFileSize) {
  auto bytes = good_tfx4();
  put(bytes, kTfx4Strands, std::uint32_t{0xffffffff});  // 4 G strands x 4 points x 16 bytes: would overflow 32 bits
  EXPECT_THAT(tfx_error(bytes), HasSubstr("file is truncated: vertex positions needs 17179869180 x 16 bytes"));
  bytes = good_tfx4();
  put(bytes, kTfx4Strands, std::uint32_t{6});  // one strand more than the file holds
  EXPECT_THAT(tfx_error(bytes), HasSubstr("vertex positions needs 24 x 16 bytes"));
}

TEST_F(HairErrors, Tfx4OffsetsIntoTheHeaderOrPastTheEnd) {
  auto bytes = good_tfx4();
  put(bytes, kTfx4Positions, std::uint32_t{0});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("bad.tfx: vertex data offset 0 points into the 160-byte header"));
  put(bytes, kTfx4Positions, std::uint32_t(bytes.size() + 8));
  EXPECT_THAT(tfx_error(bytes), HasSubstr("vertex data starts at byte 508, past the end of the file (500 bytes)"));
  bytes = good_tfx4();
  put(bytes, kTfx4Thickness, std::uint32_t{40});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("thickness offset 40 points into the header"));
  bytes = good_tfx4();
  put(bytes, kTfx4Color, std::uint32_t{200});  // inside the positions: 20 x 16 colour bytes run past the end
  EXPECT_THAT(tfx_error(bytes), HasSubstr("file is truncated: vertex colours needs 20 x 16 bytes at byte 200"));
}

TEST_F(HairErrors, Tfx4TexcoordsOutsideTheFile) {
  auto bytes = good_tfx4();
  put(bytes, kTfx4StrandUv, std::uint32_t(bytes.size() + 100));
  EXPECT_THAT(tfx_error(bytes), HasSubstr("strand texcoords starts at byte 600, past the end of the file"));
  bytes = good_tfx4();
  put(bytes, kTfx4VertexUv, std::uint32_t{480});  // 20 bytes before the end; 20 x 8 needed
  EXPECT_THAT(tfx_error(bytes), HasSubstr("file is truncated: vertex texcoords needs 20 x 8 bytes at byte 480"));
  put(bytes, kTfx4VertexUv, std::uint32_t{8});
  EXPECT_THAT(tfx_error(bytes), HasSubstr("vertex texcoord offset 8 points into the header"));
}

TEST_F(HairErrors, Tfx4NanOrInfinitePosition) {
  auto bytes = good_tfx4();
  put(bytes, 160 + 16 * 6 + 8, std::numeric_limits<float>::quiet_NaN());  // point 6's z
  EXPECT_THAT(tfx_error(bytes), AllOf(HasSubstr("bad.tfx: point 6 (strand 1) is not finite"), HasSubstr("nan")));
  bytes = good_tfx4();
  put(bytes, 160 + 16 * 19, -std::numeric_limits<float>::infinity());  // the last point's x
  EXPECT_THAT(tfx_error(bytes), AllOf(HasSubstr("point 19 (strand 4) is not finite"), HasSubstr("inf")));
  // w is the simulation's inverse mass: ignored, so a NaN there is no error.
  bytes = good_tfx4();
  put(bytes, 160 + 16 * 3 + 12, std::numeric_limits<float>::quiet_NaN());
  EXPECT_EQ(parse_tfx(bytes, "w.tfx").points, sample_groom(true).points);
}

TEST_F(HairErrors, CyHairWrongMagic) {
  auto bytes = good_hair();
  bytes[0] = std::byte{'X'};
  EXPECT_THAT(hair_error(bytes), HasSubstr("bad.hair: not a cyHair file: signature is not 'HAIR'"));
}

TEST_F(HairErrors, CyHairTruncated) {
  auto bytes = good_hair();
  EXPECT_THAT(hair_error({bytes.begin(), bytes.begin() + 60}), HasSubstr("a cyHair header needs 128 bytes, the file has 60"));
  bytes.resize(bytes.size() - 1);
  EXPECT_THAT(hair_error(bytes), HasSubstr("file is truncated: colour array"));
}

TEST_F(HairErrors, CyHairSegmentsDisagreeWithPointCount) {
  auto bytes = good_hair();
  put(bytes, 8, std::uint32_t{19});  // header: 19 points, segments describe 20
  EXPECT_THAT(hair_error(bytes), HasSubstr("segments describe more points than the 19 the header declares"));
  bytes = good_hair();
  put(bytes, 8, std::uint32_t{21});
  EXPECT_THAT(hair_error(bytes), HasSubstr("segments describe 20 points but the header declares 21"));
  put(bytes, 4, std::uint32_t{4});  // 4 strands: the segments array is one entry shorter
  EXPECT_THAT(hair_error(bytes), HasSubstr("segments describe"));
}

TEST_F(HairErrors, CyHairHugeCountsAreBoundedByTheFileSize) {
  auto bytes = good_hair();
  put(bytes, 4, std::uint32_t{0xfffffff0});  // strands
  EXPECT_THAT(hair_error(bytes), HasSubstr("declares 4294967280 strands but only 20 points"));
  put(bytes, 8, std::uint32_t{0xfffffff0});  // points
  EXPECT_THAT(hair_error(bytes), HasSubstr("file is truncated: the header declares 4294967280 points"));
}

TEST_F(HairErrors, CyHairUnknownFlagsAndMissingPoints) {
  auto bytes = good_hair();
  put(bytes, 12, std::uint32_t{0x3f});
  EXPECT_THAT(hair_error(bytes), HasSubstr("unknown array flags 63"));
  put(bytes, 12, std::uint32_t{0x01});
  EXPECT_THAT(hair_error(bytes), HasSubstr("no point array"));
}

TEST_F(HairErrors, CyHairNanPointAndBadTransparency) {
  auto bytes = good_hair();
  put(bytes, 128 + 10, std::numeric_limits<float>::infinity());
  EXPECT_THAT(hair_error(bytes), HasSubstr("point 0 (strand 0) is not finite"));
  bytes = good_hair();
  const std::size_t transparency_at = 128 + 10 + 20 * 12 + 20 * 4;
  for (int p = 0; p < 20; ++p) put(bytes, transparency_at + 4 * p, 1.5f);
  EXPECT_THAT(hair_error(bytes), HasSubstr("opacity -0.5"));
}

TEST_F(HairErrors, MissingFileAndDirectory) {
  EXPECT_THAT(load_error_of([&] { load_tfx(dir_ / "absent.tfx"); }), HasSubstr("absent.tfx: file not found"));
  EXPECT_THAT(load_error_of([&] { load_cyhair(dir_.path()); }), HasSubstr("not a regular file"));
}

}  // namespace
}  // namespace hair_test
}  // namespace avsm::scene
