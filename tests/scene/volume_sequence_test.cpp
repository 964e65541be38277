// Volume sequences (scene/frame_pattern.h, scene/volume_sequence.h): frame patterns as the
// tools write them, which frame shows when, and sequences read from files on disk,
// written here with OpenVDB as a fluid cache has them (several grids per frame).
#include "scene/frame_pattern.h"
#include "scene/scene.h"
#include "scene/volume_sequence.h"

#include <openvdb/io/File.h>
#include <openvdb/openvdb.h>

#include <fstream>

#include "support.h"

namespace avsm::scene {
namespace {

TEST(FramePattern, ReadsTheFieldsTheToolsWrite) {
  struct Case {
    const char* name;
    const char* frame_7;
    int digits;
  };
  for (const Case& c : {Case{"smoke.####.vdb", "smoke.0007.vdb", 4}, Case{"smoke.$F4.vdb", "smoke.0007.vdb", 4},
                        Case{"smoke.$F.vdb", "smoke.7.vdb", 0}, Case{"smoke.%04d.vdb", "smoke.0007.vdb", 4},
                        Case{"smoke_%d.vdb", "smoke_7.vdb", 0}, Case{"fluid_data_####.vdb", "fluid_data_0007.vdb", 4},
                        Case{"a.#.vdb", "a.7.vdb", 1}}) {
    SCOPED_TRACE(c.name);
    const std::optional<FramePattern> pattern = parse_frame_pattern(std::filesystem::path("cache") / c.name);
    ASSERT_TRUE(pattern.has_value());
    EXPECT_EQ(pattern->digits, c.digits);
    EXPECT_EQ(pattern->file(7), std::filesystem::path("cache") / c.frame_7);
    EXPECT_EQ(pattern->frame_of(c.frame_7), 7);
    EXPECT_EQ(pattern->written, c.name);
  }
}

TEST(FramePattern, MatchesOnlyItsOwnFiles) {
  const FramePattern pattern = *parse_frame_pattern("smoke.####.vdb");
  EXPECT_EQ(pattern.frame_of("smoke.0120.vdb"), 120);
  EXPECT_EQ(pattern.frame_of("smoke.12345.vdb"), 12345);  // past the padding, as Houdini writes it
  EXPECT_FALSE(pattern.frame_of("smoke.012.vdb"));        // padded otherwise
  EXPECT_FALSE(pattern.frame_of("smoke.00120.vdb"));
  EXPECT_FALSE(pattern.frame_of("smoke.00a1.vdb"));
  EXPECT_FALSE(pattern.frame_of("smoke.0001.vdb.bak"));
  EXPECT_FALSE(pattern.frame_of("fire.0001.vdb"));
  EXPECT_FALSE(parse_frame_pattern("plume.vdb").has_value());
  EXPECT_FALSE(parse_frame_pattern("100%.vdb").has_value());  // a '%' that is not a field
  EXPECT_THROW(parse_frame_pattern("smoke.####.$F4.vdb"), std::invalid_argument);
}

TEST(SequenceTiming, HoldsOrLoopsOutsideItsFrames) {
  SequenceTiming timing{10, 13, 24.0f, 10, false};
  EXPECT_EQ(timing.frame_at(0.0f), 10);
  EXPECT_EQ(timing.frame_at(1.0f / 24.0f), 11);  // exactly on a frame's time
  EXPECT_EQ(timing.frame_at(2.9f / 24.0f), 12);
  EXPECT_EQ(timing.frame_at(10.0f), 13);  // held
  EXPECT_EQ(timing.frame_at(-1.0f), 10);
  timing.loop = true;
  EXPECT_EQ(timing.frame_at(4.0f / 24.0f), 10);
  EXPECT_EQ(timing.frame_at(6.0f / 24.0f), 12);
  EXPECT_EQ(timing.frame_at(-1.0f / 24.0f), 13);
  timing.offset = 12;  // frame 12 at time 0
  EXPECT_EQ(timing.frame_at(0.0f), 12);
  EXPECT_EQ(timing.frame_at(2.0f / 24.0f), 10);
}

// A small fluid cache: frame f is a cube of density f / 10 whose side grows with f, next
// to the grids a simulation writes too.
void write_cache_frame(const std::filesystem::path& file, int frame) {
  openvdb::initialize();
  auto density = openvdb::FloatGrid::create(0.0f);
  density->setName("density");
  density->setGridClass(openvdb::GRID_FOG_VOLUME);
  density->setTransform(openvdb::math::Transform::createLinearTransform(0.1));
  auto temperature = density->deepCopy();
  temperature->setName("temperature");
  auto velocity = openvdb::Vec3SGrid::create(openvdb::Vec3f(0.0f));
  velocity->setName("velocity");
  const int side = 4 + frame;
  density->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(side - 1)), float(frame) / 10.0f);
  temperature->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(2)), 1.0f);
  velocity->fill(openvdb::CoordBBox(openvdb::Coord(0), openvdb::Coord(2)), openvdb::Vec3f(0, 1, 0));
  openvdb::io::File vdb(file.string());
  vdb.write({velocity, temperature, density});
  vdb.close();
}

VolumeEntry cache_entry(const std::filesystem::path& file) {
  VolumeEntry entry;
  entry.name = "smoke";
  entry.file = file;
  entry.grid = "density";
  return entry;
}

TEST(VolumeSequence, ReadsTheFramesOnDiskWithTheirBounds) {
  testing::TempDir dir;
  for (int frame = 3; frame <= 6; ++frame) write_cache_frame(dir.path() / ("fluid_data_000" + std::to_string(frame) + ".vdb"), frame);
  const VolumeEntry entry = cache_entry(dir.path() / "fluid_data_####.vdb");
  const VolumeSequence sequence = open_volume_sequence(entry, *parse_frame_pattern(entry.file), 0);
  EXPECT_EQ(sequence.timing.first, 3);
  EXPECT_EQ(sequence.timing.last, 6);
  EXPECT_EQ(sequence.timing.offset, 3);  // the first frame at time 0
  // The largest frame's support: voxels 0..9 of 0.1, one voxel out either side.
  EXPECT_NEAR(sequence.bounds.min.x, -0.1f, 1e-5f);
  EXPECT_NEAR(sequence.bounds.max.x, 1.0f, 1e-5f);
  const Volume frame_5 = sequence.load_frame(5);
  EXPECT_EQ(frame_5.name, "smoke");
  EXPECT_FLOAT_EQ(frame_5.stats.max, 0.5f);
  EXPECT_EQ(frame_5.stats.active_voxel_count, 9u * 9u * 9u);
}

TEST(VolumeSequence, AMissingFrameIsAnErrorNamingItsFileAndFrame) {
  testing::TempDir dir;
  for (int frame : {1, 2, 4}) write_cache_frame(dir.path() / ("smoke." + std::to_string(frame) + ".vdb"), frame);
  VolumeEntry entry = cache_entry(dir.path() / "smoke.$F.vdb");
  const std::string message = testing::load_error_of([&] { open_volume_sequence(entry, *parse_frame_pattern(entry.file), 0); });
  EXPECT_THAT(message, AllOf(HasSubstr("smoke.3.vdb"), HasSubstr("frame 3 of the sequence 'smoke.$F.vdb' is missing"),
                             HasSubstr("\"frames\"")));
  entry.sequence.first = 1;  // the frames there are
  entry.sequence.last = 2;
  EXPECT_EQ(open_volume_sequence(entry, *parse_frame_pattern(entry.file), 0).timing.last, 2);
}

TEST(VolumeSequence, ABrokenFrameIsAnErrorNamingItsFileAndFrame) {
  testing::TempDir dir;
  for (int frame = 1; frame <= 3; ++frame) write_cache_frame(dir.path() / ("smoke.000" + std::to_string(frame) + ".vdb"), frame);
  const std::vector<std::byte> bytes = testing::read_bytes(dir.path() / "smoke.0002.vdb");
  testing::write_bytes(dir.path() / "smoke.0002.vdb", {bytes.begin(), bytes.begin() + std::ptrdiff_t(bytes.size() / 2)});
  const VolumeEntry entry = cache_entry(dir.path() / "smoke.%04d.vdb");
  const std::string message = testing::load_error_of([&] { open_volume_sequence(entry, *parse_frame_pattern(entry.file), 0); });
  EXPECT_THAT(message, AllOf(HasSubstr("smoke.0002.vdb"), HasSubstr("frame 2 of the sequence 'smoke.%04d.vdb'")));
}

TEST(VolumeSequence, ASceneFileSequencePlaysItsFramesAndHoldsTheirBounds) {
  testing::TempDir dir;
  std::filesystem::create_directories(dir.path() / "cache");
  for (int frame = 1; frame <= 4; ++frame) write_cache_frame(dir.path() / "cache" / ("smoke.000" + std::to_string(frame) + ".vdb"), frame);
  testing::write_text(dir / "scene.json", R"({
    "version": 1,
    "volumes": [{ "file": "cache/smoke.####.vdb", "grid": "density", "extinction_scale": 2,
                  "sequence": { "frames": [1, 4], "fps": 12, "offset": 2, "mode": "loop" } }],
    "lights": [{ "type": "directional", "direction": [0, -1, 0] }],
    "cameras": [{ "position": [0, 0, 5], "target": [0, 0, 0], "vertical_fov_deg": 40, "near": 0.1, "far": 50 }]
  })");
  const Scene scene = load_scene(dir / "scene.json");
  ASSERT_EQ(scene.volume_sequences.size(), 1u);
  const VolumeSequence& sequence = scene.volume_sequences[0];
  EXPECT_EQ(sequence.timing.frame_at(0.0f), 2);
  EXPECT_EQ(sequence.timing.frame_at(3.0f / 12.0f), 1);  // looped
  EXPECT_FLOAT_EQ(scene.volumes[0].stats.max, 0.2f);     // frame 2 at time 0
  EXPECT_FLOAT_EQ(scene.volumes[0].extinction_scale, 2.0f);
  EXPECT_TRUE(scene.moves());
  EXPECT_FLOAT_EQ(scene.duration(), 3.0f / 12.0f);  // from frame 2 to the end of frame 4
  EXPECT_NEAR(scene.bounds.max.x, 0.8f, 1e-5f);     // to frame 4's 8 voxels, not frame 2's 6
}

TEST(VolumeSequence, SequenceSettingsNeedAFramePattern) {
  testing::TempDir dir;
  write_cache_frame(dir / "plume.vdb", 1);
  const auto scene_with = [&](const std::string& volume) {
    testing::write_text(dir / "scene.json", R"({ "version": 1, "volumes": [)" + volume + R"(],
      "lights": [{ "type": "directional", "direction": [0, -1, 0] }], "cameras": [{ "position": [0, 0, 5], "target": [0, 0, 0], "vertical_fov_deg": 40, "near": 0.1, "far": 50 }] })");
    return testing::load_error_of([&] { load_scene(dir / "scene.json"); });
  };
  EXPECT_THAT(scene_with(R"({ "file": "plume.vdb", "grid": "density", "extinction_scale": 1, "sequence": { "fps": 24 } })"),
              AllOf(HasSubstr("volumes[0].sequence"), HasSubstr("frame number field")));
  EXPECT_THAT(scene_with(R"({ "file": "p.####.vdb", "grid": "density", "extinction_scale": 1, "sequence": { "frames": [5, 2] } })"),
              AllOf(HasSubstr("volumes[0].sequence.frames"), HasSubstr("first <= last")));
  EXPECT_THAT(scene_with(R"({ "file": "p.####.vdb", "grid": "density", "extinction_scale": 1, "sequence": { "mode": "bounce" } })"),
              AllOf(HasSubstr("volumes[0].sequence.mode"), HasSubstr("hold")));
  EXPECT_THAT(scene_with(R"({ "file": "p.####.%d.vdb", "grid": "density", "extinction_scale": 1 })"),
              AllOf(HasSubstr("volumes[0].file"), HasSubstr("2 frame number fields")));
}

TEST(VolumeSequence, TheGeneratedPlumeSequenceLoads) {
  const Scene scene = load_scene(testing::default_content("plume_sequence.scene.json"));
  ASSERT_EQ(scene.volume_sequences.size(), 1u);
  const VolumeSequence& sequence = scene.volume_sequences[0];
  EXPECT_EQ(sequence.timing.count(), 24);
  // It moves: frames differ, and the smoke rises (the last frame's top is higher).
  const Volume first = sequence.load_frame(1), last = sequence.load_frame(24);
  EXPECT_NE(first.stats.active_voxel_count, last.stats.active_voxel_count);
  EXPECT_GT(last.world_bounds.max.y, first.world_bounds.max.y);
  EXPECT_TRUE(sequence.bounds.contains(last.world_bounds));
}

}  // namespace
}  // namespace avsm::scene
