// The regression gate (engine/sweep/compare.h) on synthetic reports: each check's
// threshold logic, the settings of the two sides, the thresholds file, sweep folders
// matched by id, and the outputs.
// CPU only; the real captures are compared in tests/sweep/CMakeLists.txt.
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <functional>
#include <nlohmann/json.hpp>
#include <string>

#include "capture/files.h"
#include "capture/image_difference.h"
#include "io/image_io.h"
#include "sweep/compare.h"
#include "sweep/sweep_index.h"

namespace avsm::sweep {
namespace compare_test {  // one per file: test targets are unity builds
namespace {
namespace fs = std::filesystem;
using nlohmann::json;

// Of the running test: CTest runs the tests of this file as parallel processes.
fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) /
                       ("avsm_compare_" + name + "_" + testing::UnitTest::GetInstance()->current_test_info()->name());
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

// A frame of 60 ms + the big pass: a big pass (40 ms), a 10 ms pass and a tiny one.
capture::TimingReport timings(double big_ms = 40.0, double small_ms = 0.2) {
  capture::TimingReport t;
  t.passes = {{"big", rg::QueueType::Graphics, {big_ms, big_ms, big_ms}, {}},
              {"medium", rg::QueueType::Compute, {10, 10, 10}, {}},
              {"tiny", rg::QueueType::Compute, {small_ms, small_ms, small_ms}, {}}};
  const double frame = 60.0 + big_ms;
  t.frame_gpu_ms = {frame, frame, frame};
  t.frames = {{frame, frame, frame}};
  return t;
}

capture::MemoryReport memory(uint64_t map_bytes = 1 << 20) {
  capture::MemoryReport m;
  m.transient_bytes_aliased = 4 << 20;
  passes::LightShadowStats sun;
  sun.light = "sun";
  sun.map_bytes = map_bytes;
  sun.capture_bytes = 2 << 20;
  m.lights = {sun};
  return m;
}

capture::QualityReport quality(double mean) {
  capture::LightQuality sun;
  sun.light = "sun";
  sun.surface = {1000, mean * 1000, 0.25};
  return {96, 54, {sun}};
}

// Two lights at 96x54, as settings.json holds them; AVSM-`nodes` for the sun.
capture::SettingsReport settings(int nodes = 8) {
  capture::SettingsReport s;
  s.scene = "default/scene.json";
  s.camera = "main";
  s.width = 96;
  s.height = 54;
  s.frames = 1;
  s.frames_in_flight = 2;
  s.validation = true;
  capture::LightSettings sun{"sun", scene::LightType::directional, {}, 0};
  sun.shadow.nodes = nodes;
  sun.shadow.resolution = 32;
  capture::LightSettings spot{"key_spot", scene::LightType::spot, {}, 0};
  spot.shadow.technique = "osm";
  spot.shadow.parameters = {{"slices", 32.0}};
  s.lights = {sun, spot};
  return s;
}

capture::FrameReport report(std::optional<capture::SettingsReport> settings, capture::MemoryReport m = memory()) {
  capture::FrameReport r;
  r.timings = timings();
  r.timings.width = 96;
  r.timings.height = 54;
  r.memory = std::move(m);
  r.settings = std::move(settings);
  return r;
}

gpu::ImageRGBA32F image(float value, uint32_t width = 8, uint32_t height = 4) {
  return {width, height, std::vector<float>(size_t(width) * height * 4, value)};
}

const Check* find(const std::vector<Check>& checks, const std::string& name) {
  const auto found = std::find_if(checks.begin(), checks.end(), [&](const Check& c) { return c.name == name; });
  return found == checks.end() ? nullptr : &*found;
}

size_t failures(const std::vector<Check>& checks) { return SuiteResult{"", checks}.failures(); }

// ---- thresholds ----

TEST(GateThresholds, AFileOverridesOnlyTheKeysItSets) {
  const Thresholds t = thresholds_from_json(json::parse(R"({"timing": {"max_pass_ratio": 3, "judge_cpu_devices": true},
                                                            "memory": {"min_increase_bytes": 0}})"));
  Thresholds expected;
  expected.timing.max_pass_ratio = 3.0;
  expected.timing.judge_cpu_devices = true;
  expected.memory.min_increase_bytes = 0;
  EXPECT_EQ(t, expected);
  EXPECT_EQ(thresholds_from_json(to_json(expected)), expected);  // every key written reads back
}

TEST(GateThresholds, UnknownKeysAndBadValuesAreNamed) {
  const auto error_of = [](const char* text) {
    try {
      thresholds_from_json(json::parse(text));
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of(R"({"timing": {"max_pass_rate": 2}})"),
            "unknown key \"timing.max_pass_rate\" (known in \"timing\": max_pass_ratio, min_pass_ms, "
            "min_pass_share, max_frame_ratio, judge_cpu_devices)");
  EXPECT_EQ(error_of(R"({"timing": {"judge_cpu_devices": 1}})"), "\"timing.judge_cpu_devices\": expected true or false");
  EXPECT_EQ(error_of(R"({"speed": {}})"), "unknown section \"speed\" (known: timing, image, quality, memory)");
  EXPECT_EQ(error_of(R"({"image": {"min_psnr_db": "40"}})"), "\"image.min_psnr_db\": expected a number");
  EXPECT_EQ(error_of(R"({"memory": {"max_ratio": 0.5}})"), "\"memory.max_ratio\": 0.5 is below 1.0");
  EXPECT_EQ(error_of(R"({"memory": {"min_increase_bytes": 1.5}})"),
            "\"memory.min_increase_bytes\": expected a whole number of bytes");
  EXPECT_EQ(error_of("[]"), "expected an object of sections (timing, image, quality, memory)");
}

TEST(GateThresholds, FileErrorsNameTheFile) {
  const fs::path dir = fresh_folder("thresholds");
  capture::write_text(dir / "bad.json", R"({"quality": {"max_increase": 0.1}})");
  try {
    read_thresholds(dir / "bad.json");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "bad.json").string() + ": unknown key \"quality.max_increase\" (known in "
                                                                   "\"quality\": max_mean_abs_error_increase)");
  }
  try {
    read_thresholds(dir / "missing.json");
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), (dir / "missing.json").string() + ": no such file (--thresholds)");
  }
}

// ---- timings ----

TEST(GateTimings, EqualReportsPass) {
  const std::vector<Check> checks = compare_timings(timings(), timings(), {});
  EXPECT_EQ(failures(checks), 0u);
  EXPECT_EQ(find(checks, "gpu_ms 'big'")->verdict, Verdict::pass);
  EXPECT_EQ(find(checks, "gpu_ms 'big'")->change, "x1.00");
  EXPECT_EQ(find(checks, "gpu_ms 'tiny'")->verdict, Verdict::listed);  // 0.2 ms: too short to judge
}

TEST(GateTimings, ABigPassTwiceAsSlowFails) {
  const std::vector<Check> checks = compare_timings(timings(40), timings(90), {});
  const Check* big = find(checks, "gpu_ms 'big'");
  ASSERT_TRUE(big);
  EXPECT_EQ(big->verdict, Verdict::fail);
  EXPECT_EQ(big->change, "x2.25");
  EXPECT_EQ(big->message, "pass 'big' took x2.25 its BASE time (limit x1.50, timing.max_pass_ratio)");
  EXPECT_EQ(find(checks, "frame gpu_ms")->verdict, Verdict::pass);  // 150 / 100 ms: not above x1.50
  EXPECT_EQ(find(checks, "gpu_ms 'medium'")->verdict, Verdict::pass);
  EXPECT_EQ(find(checks, "gpu_ms 'tiny'")->message, "too short to judge (< 0.5 ms or < 5% of the frame)");
}

TEST(GateTimings, NoiseInSmallPassesIsNotJudged) {
  // 0.2 -> 3 ms: 15 times longer, as a scheduler slice makes it on a busy machine, but
  // 3% of the frame.
  const std::vector<Check> checks = compare_timings(timings(40, 0.2), timings(40, 3.0), {});
  EXPECT_EQ(find(checks, "gpu_ms 'tiny'")->verdict, Verdict::listed);
  EXPECT_EQ(failures(checks), 0u);
  // With a floor low enough, the same pass is judged.
  TimingThresholds strict;
  strict.min_pass_share = 0.0;
  EXPECT_EQ(find(compare_timings(timings(40, 0.2), timings(40, 3.0), strict), "gpu_ms 'tiny'")->verdict, Verdict::fail);
}

TEST(GateTimings, ACpuDevicesTimesAreListedNotJudged) {
  capture::TimingReport slow = timings(90);
  slow.cpu_device = true;
  const std::vector<Check> checks = compare_timings(timings(40), slow, {});
  EXPECT_EQ(failures(checks), 0u);
  EXPECT_EQ(find(checks, "gpu_ms 'big'")->change, "x2.25");  // still reported
  EXPECT_EQ(find(checks, "gpu_ms 'big'")->message, "not judged on a CPU device (timing.judge_cpu_devices)");
  TimingThresholds judged;
  judged.judge_cpu_devices = true;
  EXPECT_EQ(failures(compare_timings(timings(40), slow, judged)), 1u);
}

TEST(GateTimings, TheFrameRatioAndPassesOnOneSide) {
  capture::TimingReport slow = timings(40);
  slow.frame_gpu_ms = {250, 250, 250};
  slow.passes.push_back({"new pass", rg::QueueType::Graphics, {150, 150, 150}, {}});
  slow.passes.erase(slow.passes.begin() + 1);  // "medium" gone
  const std::vector<Check> checks = compare_timings(timings(40), slow, {});
  EXPECT_EQ(find(checks, "frame gpu_ms")->verdict, Verdict::fail);
  EXPECT_EQ(find(checks, "frame gpu_ms")->change, "x2.50");
  EXPECT_EQ(find(checks, "gpu_ms 'medium'")->message, "only in BASE");
  EXPECT_EQ(find(checks, "gpu_ms 'new pass'")->message, "only in NEW");
  EXPECT_EQ(failures(checks), 1u);
}

// ---- quality ----

TEST(GateQuality, AMeanErrorRiseAboveTheLimitFails) {
  EXPECT_EQ(failures(compare_quality(quality(0.010), quality(0.0115), {})), 0u);  // +0.0015 <= 0.002
  const std::vector<Check> checks = compare_quality(quality(0.010), quality(0.013), {});
  const Check* mean = find(checks, "quality 'sun' mean_abs_error");
  ASSERT_TRUE(mean);
  EXPECT_EQ(mean->verdict, Verdict::fail);
  EXPECT_EQ(mean->change, "+0.00300");
  EXPECT_EQ(find(checks, "quality 'sun' max_abs_error")->verdict, Verdict::listed);
  EXPECT_EQ(failures(compare_quality(quality(0.013), quality(0.010), {})), 0u);  // better is fine
}

TEST(GateQuality, OneSideWithoutQualityIsListed) {
  EXPECT_TRUE(compare_quality(std::nullopt, std::nullopt, {}).empty());
  const std::vector<Check> checks = compare_quality(quality(0.01), std::nullopt, {});
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_EQ(checks[0].verdict, Verdict::listed);
  EXPECT_EQ(checks[0].message, "only in BASE (capture both with --compare-to uncompressed)");
}

// ---- memory ----

TEST(GateMemory, AGrowthAboveRatioAndFloorFails) {
  const std::vector<Check> checks = compare_memory(memory(1 << 20), memory(4 << 20), {});
  const Check* map = find(checks, "memory 'sun' map_bytes");
  ASSERT_TRUE(map);
  EXPECT_EQ(map->verdict, Verdict::fail);
  EXPECT_EQ(map->base, "1.00 MiB");
  EXPECT_EQ(map->change, "x4.00");
  EXPECT_EQ(failures(checks), 1u);
  // x2, but by 4 KiB only: under memory.min_increase_bytes.
  EXPECT_EQ(failures(compare_memory(memory(4096), memory(8192), {})), 0u);
  EXPECT_EQ(failures(compare_memory(memory(4 << 20), memory(1 << 20), {})), 0u);  // smaller is fine
}

// ---- settings ----

TEST(GateSettings, TheSameSettingsPass) {
  const std::vector<Check> checks = compare_settings(report(settings()), report(settings()), {});
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_EQ(checks[0].name, "settings");
  EXPECT_EQ(checks[0].verdict, Verdict::pass);
  EXPECT_EQ(checks[0].base, "53 settings");  // 20 of the frame, 16 of the sun, 17 of the spot (a parameter)
}

TEST(GateSettings, EachDifferenceFailsNamingTheSetting) {
  const auto differences = [](const capture::SettingsReport& now) {
    return compare_settings(report(settings()), report(now), {});
  };
  // AVSM-8 against AVSM-4, the defect that made this check: one failure, named.
  const std::vector<Check> nodes = differences(settings(4));
  ASSERT_EQ(nodes.size(), 1u);
  EXPECT_EQ(nodes[0].name, "setting 'light sun' nodes");
  EXPECT_EQ(nodes[0].base, "8");
  EXPECT_EQ(nodes[0].now, "4");
  EXPECT_EQ(nodes[0].verdict, Verdict::fail);
  EXPECT_EQ(nodes[0].message,
            "setting 'light sun' nodes is 8 in BASE but 4 in NEW: the figures compare different settings "
            "(--allow-different-settings compares them anyway)");

  capture::SettingsReport technique = settings();
  technique.lights[0].shadow.technique = "dsm";
  EXPECT_EQ(find(differences(technique), "setting 'light sun' technique")->now, "dsm");

  capture::SettingsReport resolution = settings();
  resolution.lights[1].shadow.resolution = 512;
  resolution.lights[1].lowered_to = 256;  // and the budget lowered it
  const std::vector<Check> lowered = differences(resolution);
  EXPECT_EQ(failures(lowered), 2u);
  EXPECT_EQ(find(lowered, "setting 'light key_spot' resolution")->base, "1024");
  EXPECT_EQ(find(lowered, "setting 'light key_spot' lowered_to")->now, "256");

  capture::SettingsReport size = settings();
  size.width = 128;
  size.height = 72;
  const std::vector<Check> sized = differences(size);
  EXPECT_EQ(failures(sized), 2u);
  EXPECT_EQ(find(sized, "setting width")->now, "128");
  EXPECT_EQ(find(sized, "setting height")->now, "72");

  capture::SettingsReport scene = settings();
  scene.scene = "content/real_assets.scene.json";
  const std::vector<Check> scenes = differences(scene);
  ASSERT_EQ(scenes.size(), 1u);
  EXPECT_EQ(scenes[0].name, "setting scene");
  EXPECT_EQ(scenes[0].verdict, Verdict::fail);

  // Numbers differ at all or not at all, and show as written.
  capture::SettingsReport blend = settings();
  blend.lights[0].shadow.cascade_blend = std::nextafter(0.1f, 1.0f);
  const std::vector<Check> blends = differences(blend);
  ASSERT_EQ(blends.size(), 1u);
  EXPECT_EQ(blends[0].name, "setting 'light sun' cascade_blend");
  EXPECT_EQ(blends[0].base, "0.1");
  EXPECT_EQ(blends[0].now, "0.10000001");

  // A parameter set on one side only, the volume shading, a light on one side only.
  capture::SettingsReport more = settings();
  more.lights[1].shadow.parameters["depth_bias"] = 0.01;
  more.volume_shading.mode = scene::VolumeShading::Mode::reference;
  more.lights.push_back({"lamp", scene::LightType::point, {}, 0});
  const std::vector<Check> added = differences(more);
  EXPECT_EQ(failures(added), 3u);
  EXPECT_EQ(find(added, "setting 'light key_spot' parameters.depth_bias")->base, "-");
  EXPECT_EQ(find(added, "setting 'light key_spot' parameters.depth_bias")->message.substr(0, 68),
            "setting 'light key_spot' parameters.depth_bias is only in NEW (0.01)");
  EXPECT_EQ(find(added, "setting volume_shading.mode")->now, "reference");
  EXPECT_EQ(find(added, "setting 'light lamp'")->message,
            "setting 'light lamp' is only in NEW: the figures compare different settings "
            "(--allow-different-settings compares them anyway)");
}

TEST(GateSettings, AllowedDifferencesAreListedNotFailed) {
  capture::SettingsReport now = settings(4);
  now.scene = "examples/alpha_casters.scene.json";
  const std::vector<Check> checks = compare_settings(report(settings()), report(now), {.allow_different_settings = true});
  ASSERT_EQ(checks.size(), 2u);
  EXPECT_EQ(failures(checks), 0u);
  for (const Check& check : checks) {
    EXPECT_EQ(check.verdict, Verdict::listed);
    EXPECT_EQ(check.message, "differs (allowed by --allow-different-settings)");
  }
  EXPECT_EQ(find(checks, "setting 'light sun' nodes")->now, "4");
  EXPECT_EQ(find(checks, "setting scene")->now, "examples/alpha_casters.scene.json");
}

// Capture folders written before settings.json: what timings.json and memory.json record.
TEST(GateSettings, WithoutSettingsJsonTheRecordedSettingsAreCompared) {
  const std::vector<Check> equal = compare_settings(report(std::nullopt), report(settings()), {});
  ASSERT_EQ(equal.size(), 2u);
  EXPECT_EQ(equal[0].name, "settings.json");
  EXPECT_EQ(equal[0].verdict, Verdict::listed);
  EXPECT_EQ(equal[0].base, "-");
  EXPECT_EQ(equal[0].now, "yes");
  EXPECT_EQ(equal[0].message,
            "missing in BASE (captured before it was written): only the image size and each light's technique, "
            "nodes, resolution, map_kind and build (timings.json, memory.json) are compared");
  EXPECT_EQ(equal[1].name, "settings");
  EXPECT_EQ(equal[1].verdict, Verdict::pass);
  EXPECT_EQ(equal[1].base, "7 settings");  // width, height; the sun's 5

  capture::MemoryReport four = memory();
  four.lights[0].nodes = 4;
  four.lights[0].fixed_build = passes::FixedBuildStats{};
  capture::FrameReport smaller = report(settings(), four);
  smaller.timings.width = 48;
  const std::vector<Check> checks = compare_settings(report(std::nullopt), smaller, {});
  EXPECT_EQ(failures(checks), 3u);
  EXPECT_EQ(find(checks, "setting 'light sun' nodes")->now, "4");
  EXPECT_EQ(find(checks, "setting 'light sun' build")->now, "fixed");
  EXPECT_EQ(find(checks, "setting width")->now, "48");
  EXPECT_EQ(find(checks, "settings.json")->verdict, Verdict::listed);
  EXPECT_EQ(find(compare_settings(report(settings()), report(std::nullopt), {}), "settings.json")->message.substr(0, 14),
            "missing in NEW");
  EXPECT_EQ(failures(compare_settings(report(std::nullopt), smaller, {.allow_different_settings = true})), 0u);
}

// ---- images ----

TEST(GateImages, PsnrAndMeanAbsoluteErrorOnCompressedRgb) {
  using capture::image_difference, capture::ImageDifference;
  const ImageDifference equal = image_difference(image(0.5f), image(0.5f));
  EXPECT_TRUE(std::isinf(equal.psnr_db));
  EXPECT_EQ(equal.mean_abs_error, 0.0);
  // 1/9 maps to 0.1 by x / (1 + x): a difference of 0.1 everywhere, MSE 0.01, PSNR 20 dB.
  // Alpha is not compared.
  gpu::ImageRGBA32F brighter = image(1.0f / 9.0f);
  for (size_t i = 3; i < brighter.pixels.size(); i += 4) brighter.pixels[i] = 1.0f;
  const ImageDifference d = image_difference(image(0.0f), brighter);
  EXPECT_NEAR(d.psnr_db, 20.0, 1e-4);
  EXPECT_NEAR(d.mean_abs_error, 0.1, 1e-6);
  // HDR highlights still count: 3 and 7 map to 0.75 and 0.875.
  EXPECT_NEAR(image_difference(image(3.0f), image(7.0f)).mean_abs_error, 0.125, 1e-6);
  // A NaN differs by the whole range.
  gpu::ImageRGBA32F broken = image(0.0f);
  broken.pixels[0] = std::nanf("");
  EXPECT_NEAR(image_difference(image(0.0f), broken).mean_abs_error, 1.0 / double(8 * 4 * 3), 1e-9);
  EXPECT_TRUE(std::isinf(image_difference(broken, broken).psnr_db));

  const std::vector<Check> checks = compare_images(image(0.0f), brighter, {});
  EXPECT_EQ(find(checks, "image psnr")->verdict, Verdict::fail);
  EXPECT_EQ(find(checks, "image psnr")->message, "frame.exr differs from BASE: PSNR 20.00 dB (limit 40 dB, image.min_psnr_db)");
  EXPECT_EQ(find(checks, "image mean_abs_error")->verdict, Verdict::fail);
  EXPECT_EQ(failures(compare_images(image(0.5f), image(0.5f), {})), 0u);
}

TEST(GateImages, DifferentSizesAreAClearFailure) {
  const std::vector<Check> checks = compare_images(image(0.5f, 8, 4), image(0.5f, 4, 4), {});
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_EQ(checks[0].verdict, Verdict::fail);
  EXPECT_EQ(checks[0].message,
            "frame.exr is 8x4 in BASE but 4x4 in NEW: compare captures made with the same --width and --height");
}

// ---- folders ----

void write_capture(const fs::path& dir, double big_ms, float pixel, std::optional<double> mean_error = {},
                   std::optional<capture::SettingsReport> settings = {}) {
  fs::create_directories(dir);
  capture::write_json(dir / "timings.json", capture::to_json(timings(big_ms)));
  if (settings) capture::write_json(dir / "settings.json", capture::to_json(*settings));
  capture::write_json(dir / "memory.json", capture::to_json(memory()));
  if (mean_error) capture::write_json(dir / "quality.json", capture::to_json(quality(*mean_error)));
  io::write_exr(dir / "frame.exr", image(pixel));
}

JobRecord job(const std::string& id, JobStatus status, const std::string& error = "") {
  JobRecord record;
  record.id = id;
  record.output = id;
  record.status = status;
  record.exit_code = status == JobStatus::done ? 0 : 1;
  record.error = error;
  return record;
}

// BASE: a, b, c, gone done. NEW: a equal, b darker and with 4 nodes, c failed, d only in NEW.
std::pair<fs::path, fs::path> sweep_pair() {
  const fs::path base = fresh_folder("sweep_base"), now = fresh_folder("sweep_new");
  for (const char* id : {"a", "b", "c", "gone"}) write_capture(base / id, 40, 0.5f, 0.01, settings());
  write_index(base, {"/m.json", {job("a", JobStatus::done), job("b", JobStatus::done), job("c", JobStatus::done),
                                 job("gone", JobStatus::done)}});
  write_capture(now / "a", 40, 0.5f, 0.01, settings());
  write_capture(now / "b", 40, 0.25f, 0.01, settings(4));
  write_capture(now / "d", 40, 0.5f, {}, settings());
  JobRecord b = job("b", JobStatus::done);
  b.capture_args = {"--nodes", "4"};
  write_index(now, {"/m.json", {job("a", JobStatus::done), b,
                                job("c", JobStatus::failed, "avsm-capture: error: <out of memory> & more"),
                                job("d", JobStatus::done)}});
  return {base, now};
}

// A shot folder: frames first..last as frames/frame_NNNN.png and shot.json listing them;
// frame f's pixels are `value(f)`.
void write_shot(const fs::path& dir, int first, int last, const std::function<float(int)>& value) {
  nlohmann::json frames = nlohmann::json::array();
  fs::create_directories(dir / "frames");
  for (int frame = first; frame <= last; ++frame) {
    const fs::path image_name = fs::path("frames") / ("frame_000" + std::to_string(frame) + ".png");
    io::write_png_raw(dir / image_name, image(value(frame)));
    frames.push_back({{"frame", frame}, {"image", image_name.generic_string()}, {"wall_ms", 10.0}});
  }
  capture::write_json(dir / "shot.json", {{"first_frame", first}, {"last_frame", last}, {"frames", frames}});
}

TEST(GateShots, FramesAreComparedOneByOneAndTheWorstIsNamed) {
  const fs::path base = fresh_folder("shot_base"), now = fresh_folder("shot_new");
  write_shot(base, 0, 3, [](int) { return 0.5f; });
  write_shot(now, 0, 3, [](int frame) { return frame == 2 ? 0.25f : 0.5f; });  // frame 2 darker
  std::vector<Check> checks = compare_shots(base, now, {});
  ASSERT_NE(find(checks, "shot worst psnr (frame 2)"), nullptr);
  EXPECT_EQ(find(checks, "shot worst psnr (frame 2)")->verdict, Verdict::fail);
  EXPECT_NE(find(checks, "shot worst psnr (frame 2)")->message.find("shot frame 2 differs from BASE's most"), std::string::npos);
  EXPECT_EQ(find(checks, "shot worst mean_abs_error (frame 2)")->verdict, Verdict::fail);
  EXPECT_EQ(find(checks, "shot frames")->verdict, Verdict::pass);

  write_shot(now, 0, 3, [](int) { return 0.5f; });  // the same frames pass
  EXPECT_EQ(failures(compare_shots(base, now, {})), 0u);
  // compare_captures reads them too.
  write_capture(base, 40, 0.5f);
  write_capture(now, 40, 0.5f);
  write_shot(now, 0, 3, [](int frame) { return frame == 1 ? 0.0f : 0.5f; });
  const SuiteResult suite = compare_captures("capture", base, now, {});
  EXPECT_NE(find(suite.checks, "shot worst psnr (frame 1)"), nullptr);
  EXPECT_EQ(suite.failures(), 2u);
}

TEST(GateShots, MissingFramesFailAndExtraFramesAreListed) {
  const fs::path base = fresh_folder("shot_base"), now = fresh_folder("shot_new");
  write_shot(base, 0, 3, [](int) { return 0.5f; });
  write_shot(now, 0, 2, [](int) { return 0.5f; });
  std::vector<Check> checks = compare_shots(base, now, {});
  EXPECT_EQ(find(checks, "shot frames")->verdict, Verdict::fail);
  EXPECT_EQ(find(checks, "shot frames")->message, "NEW lacks frames 3 of BASE's shot");
  write_shot(now, 0, 4, [](int) { return 0.5f; });
  checks = compare_shots(base, now, {});
  EXPECT_EQ(find(checks, "shot frames")->verdict, Verdict::listed);
  EXPECT_EQ(failures(checks), 0u);
  // A shot on one side only, and none on either.
  fs::remove(now / "shot.json");
  checks = compare_shots(base, now, {});
  ASSERT_EQ(checks.size(), 1u);
  EXPECT_EQ(checks[0].verdict, Verdict::fail);
  EXPECT_TRUE(compare_shots(now, now, {}).empty());
  capture::write_json(now / "shot.json", {{"frames", "not a list"}});
  EXPECT_THROW(compare_shots(base, now, {}), std::runtime_error);
}

TEST(GateFolders, SweepsAreComparedJobByJob) {
  const auto [base, now] = sweep_pair();
  const GateResult result = compare_folders(base, now, {});
  ASSERT_EQ(result.suites.size(), 5u);
  EXPECT_EQ(result.suites[0].name, "a");
  EXPECT_EQ(result.suites[0].failures(), 0u);
  EXPECT_EQ(result.suites[0].checks.at(0).name, "settings");  // settings first
  EXPECT_EQ(result.suites[1].name, "b");
  EXPECT_EQ(result.suites[1].failures(), 3u);  // the nodes setting, PSNR and mean absolute error
  EXPECT_EQ(result.suites[1].checks.at(0).message, "differ: the figures compare different settings");
  EXPECT_EQ(result.suites[1].checks.at(0).verdict, Verdict::listed);
  EXPECT_EQ(result.suites[1].checks.at(0).now, "--nodes 4");
  EXPECT_EQ(result.suites[1].checks.at(1).name, "setting 'light sun' nodes");
  EXPECT_EQ(result.suites[1].checks.at(1).verdict, Verdict::fail);
  EXPECT_EQ(result.suites[2].name, "c");
  EXPECT_EQ(result.suites[2].checks.at(0).message,
            "job 'c' was done in BASE but is failed in NEW: avsm-capture: error: <out of memory> & more");
  EXPECT_EQ(result.suites[3].checks.at(0).message, "only in BASE");
  EXPECT_EQ(result.suites[4].name, "d");
  EXPECT_EQ(result.suites[4].checks.at(0).message, "only in NEW");
  EXPECT_EQ(result.failures(), 4u);

  // Allowed: the job's settings are listed, its image still fails.
  const GateResult allowed = compare_folders(base, now, {}, {.allow_different_settings = true});
  EXPECT_EQ(allowed.suites[1].failures(), 2u);
  EXPECT_EQ(find(allowed.suites[1].checks, "setting 'light sun' nodes")->verdict, Verdict::listed);
  EXPECT_EQ(allowed.failures(), 3u);
}

TEST(GateFolders, CapturePairsAndBadInputs) {
  const fs::path base = fresh_folder("capture_base"), now = fresh_folder("capture_new");
  write_capture(base, 40, 0.5f, 0.01);
  write_capture(now, 40, 0.5f, 0.01);
  const GateResult equal = compare_folders(base, now, {});
  ASSERT_EQ(equal.suites.size(), 1u);
  EXPECT_EQ(equal.suites[0].name, "capture");
  EXPECT_EQ(equal.failures(), 0u);
  EXPECT_TRUE(find(equal.suites[0].checks, "quality 'sun' mean_abs_error"));
  EXPECT_TRUE(find(equal.suites[0].checks, "memory 'sun' capture_bytes"));
  EXPECT_EQ(find(equal.suites[0].checks, "settings.json")->message.substr(0, 23), "missing in BASE and NEW");

  // settings.json read back from the folders: AVSM-8 against AVSM-4 fails on the setting alone.
  capture::write_json(base / "settings.json", capture::to_json(settings(8)));
  capture::write_json(now / "settings.json", capture::to_json(settings(4)));
  const GateResult nodes = compare_folders(base, now, {});
  EXPECT_EQ(nodes.failures(), 1u);
  EXPECT_EQ(nodes.suites[0].checks.at(0).name, "setting 'light sun' nodes");
  EXPECT_EQ(compare_folders(base, now, {}, {.allow_different_settings = true}).failures(), 0u);
  capture::write_json(now / "settings.json", capture::to_json(settings(8)));
  EXPECT_EQ(compare_folders(base, now, {}).failures(), 0u);

  const auto error_of = [](const fs::path& b, const fs::path& n) {
    try {
      compare_folders(b, n, {});
    } catch (const std::runtime_error& e) {
      return std::string(e.what());
    }
    return std::string("no error");
  };
  EXPECT_EQ(error_of(base, base / "nothing"),
            (base / "nothing").string() + ": no such folder (NEW: a capture folder or a sweep folder)");
  const auto [sweep, unused] = sweep_pair();
  EXPECT_NE(error_of(base, sweep).find("compare captures with captures, sweeps with sweeps"), std::string::npos);
  capture::write_text(now / "memory.json", "{");
  EXPECT_EQ(error_of(base, now), (now / "memory.json").string() + ": not valid JSON");
  fs::remove(now / "memory.json");
  EXPECT_EQ(error_of(base, now), (now / "memory.json").string() + ": missing or unreadable (run the capture first)");
}

// ---- outputs ----

size_t occurrences(const std::string& text, const std::string& part) {
  size_t n = 0;
  for (size_t at = text.find(part); at != std::string::npos; at = text.find(part, at + 1)) ++n;
  return n;
}

TEST(GateOutput, JunitHasASuitePerJobACasePerCheckAndEscapes) {
  const auto [base, now] = sweep_pair();
  const GateResult result = compare_folders(base, now, {});
  const std::string xml = junit_xml(result);
  size_t checks = 0;
  for (const SuiteResult& suite : result.suites) checks += suite.checks.size();
  EXPECT_EQ(occurrences(xml, "<testsuite "), 5u);
  EXPECT_EQ(occurrences(xml, "<testcase "), checks);
  EXPECT_EQ(occurrences(xml, "<failure "), 4u);
  EXPECT_NE(xml.find("<testsuites name=\"avsm-compare\" tests=\"" + std::to_string(checks) + "\" failures=\"4\""),
            std::string::npos);
  EXPECT_NE(xml.find("message=\"job &#39;c&#39; was done in BASE but is failed in NEW: avsm-capture: error: "
                     "&lt;out of memory&gt; &amp; more\""),
            std::string::npos);
  EXPECT_EQ(xml.find("<out of"), std::string::npos);
}

// Controls XML 1.0 cannot hold (a light named by a broken scene file) become '?'.
TEST(GateOutput, JunitReplacesControlCharacters) {
  const Check check{"memory 'a\x01" "b' map_bytes", "1", "2", "x2.00", "<= x1.10", Verdict::fail, "grew\x1b[0m"};
  const std::string xml = junit_xml({"base", "new", {{"job\x02", {check}}}});
  EXPECT_NE(xml.find("<testsuite name=\"job?\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("name=\"memory &#39;a?b&#39; map_bytes\""), std::string::npos) << xml;
  EXPECT_NE(xml.find("message=\"grew?[0m\""), std::string::npos) << xml;
}

TEST(GateOutput, SummaryTableAndVerdict) {
  const auto [base, now] = sweep_pair();
  const std::string text = summary_text(compare_folders(base, now, {}));
  EXPECT_NE(text.find("b: "), std::string::npos);
  EXPECT_NE(text.find("FAIL: 4 checks crossed a threshold"), std::string::npos);
  EXPECT_NE(text.find("  b: frame.exr differs from BASE: PSNR "), std::string::npos);
  EXPECT_NE(text.find("  b: setting 'light sun' nodes is 8 in BASE but 4 in NEW: the figures compare different settings"),
            std::string::npos);
  EXPECT_NE(summary_text({"x", "y", {}}).find("PASS: no threshold crossed"), std::string::npos);
}

}  // namespace
}  // namespace compare_test
}  // namespace avsm::sweep
