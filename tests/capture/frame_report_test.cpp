// The typed frame report: each JSON file it writes reads back to the same report,
// and report.html shows what the structure holds (no JSON in between).
#include <gtest/gtest.h>

#include <filesystem>
#include <fstream>
#include <iterator>
#include <map>
#include <nlohmann/json.hpp>
#include <string>

#include "capture/files.h"
#include "capture/frame_report.h"
#include "capture/report.h"
#include "gpu/transfer.h"
#include "io/image_io.h"

namespace avsm::capture {
namespace frame_report_test {  // one per file: test targets are unity builds
namespace {
namespace fs = std::filesystem;

TimingReport sample_timings() {
  TimingReport t;
  t.device = "Test GPU 9000";
  t.driver = "testdriver 1.2";
  t.timestamp_mode = "exact";
  t.cpu_device = true;
  t.width = 320;
  t.height = 180;
  t.passes = {{"light 0 capture opaque", rg::QueueType::Compute, {1.25, 1.5, 2.0}, {0.01, 0.02, 0.03}},
              {"opaque", rg::QueueType::Graphics, {3.0, 3.5, 4.0}, {0.05, 0.06, 0.07}}};
  t.frame_gpu_ms = {4.25, 5.0, 6.0};
  t.frame_wall_ms = {10.0, 11.0, 12.0};
  t.frame_submit_wall_ms = {5.0, 5.5, 6.5};
  t.frames = {{4.25, 10.0, 5.0, 1.5, 0.5, 3}, {5.0, 11.0, 5.5, 0.5, 0.0, 0}, {6.0, 12.0, 6.5, 0.25, 0.125, 1}};
  return t;
}

passes::LightShadowStats sample_light(const std::string& name, const std::string& technique) {
  passes::LightShadowStats s;
  s.light = name;
  s.technique = technique;
  s.nodes = 8;
  s.resolution = 256;
  s.mip_levels = 1;
  s.map_bytes = 2097152;
  s.capture_capacity = 524288;
  s.capture_requested = 123457;
  s.capture_bytes = 8650752;
  s.next_capture_capacity = 524288;
  if (technique == "dsm") s.dsm_pool = passes::DsmPoolStats{70000, 65536, true};
  if (technique == "avsm") s.maps = 4, s.map_kind = "clusters", s.lowered_from = 512;  // not the defaults
  return s;
}

MemoryReport sample_memory() {
  MemoryReport m;
  m.transient_bytes_aliased = 1000000;
  m.transient_bytes_unaliased = 4000000;
  m.heap_count = 2;
  m.lights = {sample_light("sun_7", "avsm"), sample_light("key_spot_42", "dsm")};
  m.scene_bounds.min = {-1.5f, 0.0f, -2.25f};
  m.scene_bounds.max = {1.5f, 3.0f, 2.25f};
  m.frames_with_capture_overflow = 1;
  m.volumes.shading.mode = scene::VolumeShading::Mode::reference;
  m.volumes.shading.resolution_divisor = 4;
  m.volumes.shading.step_voxels = 0.5f;
  m.volumes.density_atlas_bytes = 4096;
  m.volumes.lighting_cache_cells = 0;
  return m;
}

// Sums chosen so mean = sum / receivers is exact: quality.json keeps the mean.
QualityReport sample_quality() {
  LightQuality light;
  light.light = "sun_7";
  light.settings.technique = "osm";
  light.settings.filter = scene::ShadowFilter::point;
  light.settings.resolution = 64;
  light.settings.parameters = {{"slices", 32.0}};
  light.surface = {4, 0.5, 0.25};
  light.smoke = {2, 0.75, 0.5};
  return {96, 54, {light}};
}

ProbeReport sample_probes() {
  ProbeLight light;
  light.light = "sun_7";
  light.settings.technique = "uncompressed";
  light.settings.resolution = 48;
  light.transmittance = {1.0f, 0.5f};
  return {{{0.0f, 1.0f, 2.0f}, {0.25f, -0.5f, 3.0f}}, {light}};
}

// Every field away from its default, so a key that is not read back shows.
SettingsReport sample_settings() {
  SettingsReport s;
  s.scene = "examples/alpha_casters.scene.json";
  s.camera = "close_up";
  s.width = 96;
  s.height = 54;
  s.frames = 3;
  s.frames_in_flight = 1;
  s.orbit_degrees = 1.5f;
  s.light_orbit_degrees = -0.5f;
  s.validation = true;
  s.volume_shading = {scene::VolumeShading::Mode::reference, 4, 0.5f};
  s.compare_volume_shading = true;
  s.exponential_interpolation = true;
  s.compare_to_uncompressed = true;
  s.probe_points = 2;
  s.plot_texels = {"0:16,16", "key_spot:10,20"};
  s.shadows = {64.0, true, 3};
  LightSettings sun{"sun_7", scene::LightType::directional, {}, 0};
  sun.shadow = {"dsm", 12, 256, scene::ShadowFilter::trilinear, scene::ShadowKernel::gaussian, 3, false,
                scene::ShadowBuild::fixed, scene::ShadowFit::scene, 40.0f, 3, 0.25f, 0, {{"error", 0.01}}};
  LightSettings spot{"key_spot_42", scene::LightType::spot, {}, 128};
  spot.shadow.clusters = 4;
  s.lights = {sun, spot};
  return s;
}

FrameReport sample_report() {
  FrameReport report{sample_timings(), sample_memory(), {}, "digraph plan {}\n", sample_quality(), sample_probes()};
  report.plan.passes = {{"light 0 capture opaque", rg::QueueType::Compute, 3}, {"opaque", rg::QueueType::Graphics, 1}};
  report.plan.resources = {{"shadow lists", rg::ResourceKind::Buffer, "4096 bytes", false, true, 4096, 0, 0u, 0u, 1u}};
  report.plan.barrier_count = 4;
  report.plan.shape_hash = 0xbeef;
  return report;
}

std::string read_text(const fs::path& path) {
  std::ifstream in(path, std::ios::binary);
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

fs::path fresh_folder(const std::string& name) {
  const fs::path dir = fs::path(testing::TempDir()) / ("avsm_frame_report_" + name);
  fs::remove_all(dir);
  fs::create_directories(dir);
  return dir;
}

TEST(FrameReport, TimingsRoundTrip) {
  const TimingReport timings = sample_timings();
  const nlohmann::json json = to_json(timings);
  EXPECT_EQ(json["frames_measured"], 3);
  EXPECT_EQ(json["passes"][0]["queue"], "compute");
  EXPECT_EQ(timing_report_from_json(json), timings);
}

TEST(FrameReport, MemoryRoundTrip) {
  const MemoryReport memory = sample_memory();
  const nlohmann::json json = to_json(memory);
  const MemoryReport back = memory_report_from_json(json);
  EXPECT_EQ(back.lights, memory.lights);
  EXPECT_EQ(back.scene_bounds.min, memory.scene_bounds.min);
  EXPECT_EQ(back.scene_bounds.max, memory.scene_bounds.max);
  EXPECT_EQ(back.volumes.shading.mode, scene::VolumeShading::Mode::reference);
  EXPECT_EQ(back.volumes.shading.step_voxels, 0.5f);
  EXPECT_EQ(to_json(back), json);
}

// The node pool is a deep shadow map's alone: other techniques' lights have no pool keys.
TEST(FrameReport, DsmPoolKeysOnlyForDsmLights) {
  const nlohmann::json json = to_json(sample_memory());
  EXPECT_FALSE(json["lights"][0].contains("dsm_pool_capacity_nodes"));
  EXPECT_EQ(json["lights"][1]["dsm_pool_capacity_nodes"], 65536);
  EXPECT_EQ(json["lights"][1]["dsm_pool_requested_nodes"], 70000);
  EXPECT_EQ(json["lights"][1]["dsm_pool_overflowed"], true);
}

TEST(FrameReport, QualityRoundTrip) {
  const nlohmann::json json = to_json(sample_quality());
  EXPECT_EQ(json["lights"][0]["mean_abs_error"], 1.25 / 6);
  EXPECT_TRUE(json["lights"][0]["hair"]["mean_abs_error"].is_null());  // no hair receivers
  EXPECT_EQ(json["lights"][0]["error_image"], "light0_error.png");
  const QualityReport back = quality_report_from_json(json);
  EXPECT_EQ(back.lights.at(0).settings.technique, "osm");
  EXPECT_EQ(to_json(back), json);
}

// Six pixels of two lights: the summary counts each light's lit receivers, those whose
// texel is at most 1.5 pixels wide, their median, levels and needed texels (the pixel
// without a receiver left out); the file reads back.
TEST(FrameReport, ResolutionSummaryAndRoundTrip) {
  scene::Scene scene;
  scene.lights.resize(2);
  scene.lights[0].name = "sun";
  using P = passes::PixelShadowResolution;
  const std::vector<P> pixels = {
      {0.5f, 1.0f, 2.0f, 0, 1}, {-1.0f, 0.0f, 9.0f, 0, 1}, {3.0f, 2.0f, 0.5f, 0, 1},  // light 0: two receivers
      {0.0f, 1.5f, 1.0f, 1, 0}, {0.0f, 1.6f, 1.0f, 1, 0}, {0.0f, 0.4f, 1.0f, 1, 0},   // light 1: three
  };
  const ResolutionReport report = summarize_resolution(pixels, 3, 1, scene);
  ASSERT_EQ(report.lights.size(), 2u);
  EXPECT_EQ(report.lights[0].light, "sun");
  EXPECT_EQ(report.lights[1].light, "light 1");
  EXPECT_TRUE(report.lights[0].paged);
  EXPECT_FALSE(report.lights[1].paged);
  EXPECT_EQ(report.lights[0].receivers, 2u);
  EXPECT_EQ(report.lights[0].matched, 1u);
  EXPECT_EQ(report.lights[0].levels[0], 1u);
  EXPECT_EQ(report.lights[0].levels[3], 1u);
  EXPECT_DOUBLE_EQ(report.lights[0].needed_texels, 2.5);
  EXPECT_EQ(report.lights[1].matched, 2u);  // 1.5 counts, 1.6 does not
  EXPECT_FLOAT_EQ(report.lights[1].median_texel_pixels, 1.5f);
  EXPECT_EQ(report.receivers(), 5u);
  EXPECT_DOUBLE_EQ(report.matched_fraction(), 3.0 / 5.0);
  const nlohmann::json json = to_json(report);
  EXPECT_EQ(json["lights"][1]["image"], "light1_resolution.png");
  EXPECT_EQ(to_json(resolution_report_from_json(json)), json);
}

TEST(FrameReport, ProbesRoundTrip) {
  const ProbeReport probes = sample_probes();
  const nlohmann::json json = to_json(probes);
  EXPECT_EQ(to_json(probe_report_from_json(json)), json);
  EXPECT_EQ(probe_report_from_json(json).points, probes.points);
}

TEST(FrameReport, SettingsRoundTrip) {
  const nlohmann::json json = to_json(sample_settings());
  EXPECT_EQ(json["lights"][0]["technique"], "dsm");
  EXPECT_EQ(json["lights"][0]["kernel"], "gaussian");
  EXPECT_EQ(json["lights"][1]["type"], "spot");
  EXPECT_EQ(json["lights"][1]["lowered_to"], 128);
  EXPECT_EQ(json["volume_shading"]["mode"], "reference");
  EXPECT_EQ(json["shadows"]["clusters"], 3);
  const SettingsReport back = settings_report_from_json(json);
  EXPECT_EQ(to_json(back), json);  // every key read back
  EXPECT_EQ(back.lights.at(0).shadow.build, scene::ShadowBuild::fixed);
  EXPECT_EQ(back.lights.at(0).shadow.parameters, (std::map<std::string, double>{{"error", 0.01}}));
  EXPECT_EQ(back.lights.at(1).type, scene::LightType::spot);
  EXPECT_EQ(back.plot_texels, sample_settings().plot_texels);

  nlohmann::json broken = json;
  broken["lights"][1]["type"] = "area";
  try {
    settings_report_from_json(broken);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_EQ(std::string(e.what()), "lights[1]: unknown light type 'area'");
  }
}

// The scene as settings.json names it: its folder and file name, wherever the checkout is.
TEST(FrameReport, SceneLabelIsTheFolderAndFileName) {
  EXPECT_EQ(scene_label("/home/a/avsm/build/content/default/scene.json"), "default/scene.json");
  EXPECT_EQ(scene_label("/ci/checkout/content/real_assets.scene.json"), "content/real_assets.scene.json");
  EXPECT_EQ(scene_label("/ci/content/examples/../examples/alpha_casters.scene.json"),
            "examples/alpha_casters.scene.json");
  EXPECT_EQ(scene_label("alpha_casters.scene.json"),
            fs::current_path().filename().string() + "/alpha_casters.scene.json");
}

TEST(FrameReport, ReadsACaptureFolderBack) {
  const fs::path dir = fresh_folder("folder");
  const FrameReport report = sample_report();
  write_json(dir / "timings.json", to_json(report.timings));
  write_json(dir / "memory.json", to_json(report.memory));
  write_json(dir / "probes.json", to_json(*report.probes));
  const FrameReport back = read_frame_report(dir);
  EXPECT_EQ(back.timings, report.timings);
  EXPECT_EQ(back.memory.lights, report.memory.lights);
  EXPECT_FALSE(back.quality);  // no quality.json in the folder
  EXPECT_FALSE(back.settings);  // nor settings.json (as in folders captured before it was written)
  ASSERT_TRUE(back.probes);
  EXPECT_EQ(back.probes->lights.at(0).transmittance, report.probes->lights.at(0).transmittance);

  write_json(dir / "settings.json", to_json(sample_settings()));
  const FrameReport with_settings = read_frame_report(dir);
  ASSERT_TRUE(with_settings.settings);
  EXPECT_EQ(to_json(*with_settings.settings), to_json(sample_settings()));
}

// Timings written before the device kind was recorded read as a GPU's.
TEST(FrameReport, OlderTimingsHaveNoCpuDevice) {
  nlohmann::json timings = to_json(sample_timings());
  EXPECT_TRUE(timing_report_from_json(timings).cpu_device);
  timings.erase("cpu_device");
  EXPECT_FALSE(timing_report_from_json(timings).cpu_device);
}

// Frames written before the per-frame shadow, inspection and page figures were recorded
// (a baseline from an older build) read them as 0; settings without an orbit, as none.
TEST(FrameReport, OlderReportsHaveNoPerFrameFiguresOrOrbit) {
  nlohmann::json timings = to_json(sample_timings());
  for (nlohmann::json& frame : timings["frames"])
    for (const char* key : {"shadow_gpu_ms", "inspection_gpu_ms", "pages_built"}) frame.erase(key);
  const TimingReport old = timing_report_from_json(timings);
  ASSERT_EQ(old.frames.size(), sample_timings().frames.size());
  EXPECT_EQ(old.frames[0].gpu_ms, sample_timings().frames[0].gpu_ms);
  EXPECT_EQ(old.frames[0].shadow_gpu_ms, 0.0);
  EXPECT_EQ(old.frames[0].pages_built, 0u);
  nlohmann::json settings = to_json(sample_settings());
  settings.erase("orbit_degrees");
  EXPECT_EQ(settings_report_from_json(settings).orbit_degrees, 0.0f);
}

TEST(FrameReport, ABrokenFileIsNamedWithItsKey) {
  const fs::path dir = fresh_folder("broken");
  nlohmann::json timings = to_json(sample_timings());
  timings.erase("frame_wall_ms");
  write_json(dir / "timings.json", timings);
  write_json(dir / "memory.json", to_json(sample_memory()));
  try {
    read_frame_report(dir);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("timings.json: no \"frame_wall_ms\""), std::string::npos) << e.what();
  }
}

// report.html is drawn from the structure: values that exist only in it show up.
TEST(FrameReport, HtmlShowsTheStructure) {
  const fs::path dir = fresh_folder("html");
  gpu::ImageRGBA32F frame{2, 2, std::vector<float>(16, 0.5f)};
  io::write_png_raw(dir / "frame.png", frame);
  const FrameReport report = sample_report();
  write_report(dir, report, dir / "report.html");
  const std::string html = read_text(dir / "report.html");
  EXPECT_NE(html.find("<title>avsm-capture report: Test GPU 9000</title>"), std::string::npos);
  EXPECT_NE(html.find("<tr class=\"light\"><td>key_spot_42</td><td>dsm</td>"), std::string::npos);
  EXPECT_NE(html.find("<td class=\"num\">123457</td>"), std::string::npos);
  EXPECT_NE(html.find("5.500 ms median (5.000 ms \u2013 6.500 ms)"), std::string::npos);  // submit to completion
  EXPECT_NE(html.find("OSM-32"), std::string::npos);                                       // the quality table
  EXPECT_NE(html.find("<td class=\"num\">0.5000</td>"), std::string::npos);                // a probe
  EXPECT_NE(html.find("4 barriers (0 after the last pass)"), std::string::npos);
  EXPECT_NE(html.find("shape hash beef."), std::string::npos);
  EXPECT_NE(html.find("<td>0 light 0 capture opaque</td><td>1 opaque</td>"), std::string::npos);  // lifetime
  EXPECT_NE(html.find("digraph plan {}"), std::string::npos);
}

}  // namespace
}  // namespace frame_report_test
}  // namespace avsm::capture
