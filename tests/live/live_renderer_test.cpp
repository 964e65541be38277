// Hot reload through LiveRenderer: broken shaders, scene files and assets keep
// the last good content rendering and report the file (and line) at fault; the
// fixed files load again. Works on a private copy of shaders/ and of the default
// scene's stage, so the edits never touch the repository.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <filesystem>
#include <fstream>
#include <functional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <thread>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "gpu/vk_check.h"
#include "live/live_renderer.h"
#include "passes/frame/view.h"
#include "rendergraph/vulkan/executor.h"
#include "support/gpu_test.h"

namespace avsm::live {
namespace live_renderer_test {  // one per file: test targets are unity builds
namespace {
namespace fs = std::filesystem;

#ifndef AVSM_DEFAULT_SCENE
#error "AVSM_DEFAULT_SCENE names the generated default scene"
#endif

std::string read_text(const fs::path& file) {
  std::ifstream in(file);
  std::stringstream text;
  text << in.rdbuf();
  return text.str();
}

// Writes `text` and moves the time stamp forward, so the edit is seen even when
// it lands within the file system's time resolution of the previous write.
void write_text(const fs::path& file, const std::string& text) {
  const fs::file_time_type before = fs::exists(file) ? fs::last_write_time(file) : fs::file_time_type::min();
  std::ofstream(file, std::ios::trunc) << text;
  if (fs::last_write_time(file) <= before) fs::last_write_time(file, before + std::chrono::seconds(1));
}

void replace_in_file(const fs::path& file, const std::string& from, const std::string& to) {
  std::string text = read_text(file);
  const size_t at = text.find(from);
  ASSERT_NE(at, std::string::npos) << from << " not in " << file;
  text.replace(at, from.size(), to);
  write_text(file, text);
}

int line_of(const fs::path& file, const std::string& needle) {
  std::istringstream text(read_text(file));
  std::string line;
  for (int number = 1; std::getline(text, line); ++number)
    if (line.find(needle) != std::string::npos) return number;
  return 0;
}

// One small scene: the default stage (glTF), one sun with an AVSM-4 map.
constexpr const char* kSceneJson = R"({
  "version": 1,
  "models": [ { "name": "stage", "file": "stage.gltf" } ],
  "lights": [ { "name": "sun", "type": "directional", "direction": [0.35, -1.0, 0.25], "intensity": 3.0,
                "shadow": { "technique": "avsm", "nodes": 4, "resolution": 32, "filter": "bilinear" } } ],
  "cameras": [ { "position": [0.2, 1.7, 5.8], "target": [0.1, 1.1, 0.0], "vertical_fov_deg": 45.0,
                 "near": 0.05, "far": 60.0 } ]
})";

class LiveRendererTest : public testing::GpuTest {
 protected:
  void SetUp() override {
    GpuTest::SetUp();
    const auto* info = ::testing::UnitTest::GetInstance()->current_test_info();
    root_ = fs::temp_directory_path() / ("avsm_live_" + std::string(info->name()));
    fs::remove_all(root_);
    fs::create_directories(root_ / "content");
    fs::copy(fs::path(AVSM_SOURCE_ROOT) / "shaders", root_ / "shaders", fs::copy_options::recursive);
    // The shadow techniques' lookups, which the shaders include (passes/shadows/techniques/<name>/<name>.glsl).
    fs::create_directories(root_ / "passes/shadows");
    fs::copy(fs::path(AVSM_SOURCE_ROOT) / "passes/shadows/techniques", root_ / "passes/shadows/techniques", fs::copy_options::recursive);
    const fs::path stage_dir = fs::path(AVSM_DEFAULT_SCENE).parent_path();
    fs::copy_file(stage_dir / "stage.gltf", root_ / "content/stage.gltf");
    fs::copy_file(stage_dir / "stage.bin", root_ / "content/stage.bin");
    write_text(scene_file(), kSceneJson);
  }
  void TearDown() override {
    live_.reset();
    fs::remove_all(root_);
    GpuTest::TearDown();
  }

  fs::path scene_file() const { return root_ / "content/scene.json"; }
  fs::path shader(const std::string& relative) const { return root_ / "shaders" / relative; }

  // Whole-file rewrites (write_text) are read at once unless a test asks for settling.
  LiveRenderer& start(SettleTimes settle = {Clock::duration(0), Clock::duration(0)}) {
    LiveOptions options;
    options.scene_file = scene_file();
    options.width = 48;
    options.height = 32;
    options.settle = settle;
    options.before_reading = [this] {
      if (during_read_) std::exchange(during_read_, nullptr)();
    };
    // Sources from the private copy; the build's generated GLSL (the technique dispatch).
    options.shader_paths = {root_, gpu::ShaderLibrary::default_paths().spirv_root};
    live_ = std::make_unique<LiveRenderer>(ctx(), options);
    return *live_;
  }

  // Renders one frame and returns the tonemapped pixels (as floats, 8-bit exact).
  std::vector<float> render() {
    renderer::SceneRenderer& frame = live_->renderer();
    rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
    const passes::View view = passes::make_view(live_->scene().cameras.front(), frame.width(), frame.height());
    rg::Graph graph = frame.build_frame(view);
    ctx().submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
    frame.finish_frame();
    return gpu::read_image(ctx(), frame.ldr(), renderer::SceneRenderer::kOutputLayout).pixels;
  }

  fs::path root_;
  std::unique_ptr<LiveRenderer> live_;
  std::function<void()> during_read_;  // an editor's write landing while the next reload reads
};

TEST_F(LiveRendererTest, NothingChangedMeansNothingReloads) {
  LiveRenderer& live = start();
  EXPECT_FALSE(live.poll().anything_new());
  EXPECT_FALSE(live.error());
  // It watches the scene, its glTF, and the shaders with their includes.
  const std::vector<fs::path> watched = live.watched_files();
  auto watches = [&](const fs::path& file) {
    return std::find(watched.begin(), watched.end(), fs::weakly_canonical(file)) != watched.end() ||
           std::find(watched.begin(), watched.end(), file) != watched.end();
  };
  EXPECT_TRUE(watches(scene_file()));
  EXPECT_TRUE(watches(root_ / "content/stage.gltf"));
  EXPECT_TRUE(watches(root_ / "content/stage.bin"));  // the glTF's buffer
  EXPECT_TRUE(watches(shader("passes/camera/tonemap.comp")));
  EXPECT_TRUE(watches(shader("common/shadow_lookup.glsl")));
}

TEST_F(LiveRendererTest, BrokenShaderKeepsTheLastPipelineAndFixedShaderSwapsIn) {
  LiveRenderer& live = start();
  const std::vector<float> before = render();
  renderer::SceneRenderer* const good_renderer = &live.renderer();

  // A syntax error: the old pipelines keep rendering the same picture.
  const fs::path tonemap = shader("passes/camera/tonemap.comp");
  replace_in_file(tonemap, "vec3 mapped = filmic(c);", "vec3 mapped = filmic(c) oops;");
  PollResult broken = live.poll();
  EXPECT_TRUE(broken.failed);
  EXPECT_FALSE(broken.shaders_reloaded);
  ASSERT_TRUE(live.error());
  EXPECT_EQ(fs::weakly_canonical(live.error()->file), fs::weakly_canonical(tonemap));
  EXPECT_EQ(live.error()->line, line_of(tonemap, "oops"));
  // One line: where, then glslang's complaint (not a repeat of the path).
  const std::string summary = live.error()->summary();
  EXPECT_NE(summary.find("tonemap.comp:" + std::to_string(line_of(tonemap, "oops")) + ": "), std::string::npos)
      << summary;
  EXPECT_NE(summary.find("syntax error"), std::string::npos) << summary;
  EXPECT_EQ(summary.find('\n'), std::string::npos) << summary;
  EXPECT_EQ(&live.renderer(), good_renderer);
  EXPECT_EQ(render(), before);
  // Still broken, nothing new: no second attempt, the error stays up.
  EXPECT_FALSE(live.poll().failed);
  EXPECT_TRUE(live.error());

  // Fixed, and visibly different: a tonemapper that writes white everywhere.
  replace_in_file(tonemap, "vec3 mapped = filmic(c) oops;", "vec3 mapped = vec3(1.0);");
  const uint64_t pipelines_before = gpu::Pipeline::created_count();
  PollResult fixed = live.poll();
  // Only the edited shader's pipeline is new; the others are shared with the old renderer.
  EXPECT_EQ(gpu::Pipeline::created_count(), pipelines_before + 1);
  EXPECT_TRUE(fixed.shaders_reloaded);
  EXPECT_FALSE(fixed.failed);
  EXPECT_FALSE(live.error());
  const std::vector<float> white = render();
  ASSERT_EQ(white.size(), before.size());
  EXPECT_NE(white, before);
  for (size_t i = 0; i < white.size(); ++i) ASSERT_EQ(white[i], 1.0f) << "channel " << i;
}

TEST_F(LiveRendererTest, BrokenIncludeNamesTheIncludedFile) {
  LiveRenderer& live = start();
  const fs::path include = shader("common/shadow_lookup.glsl");
  std::string text = read_text(include);
  write_text(include, text + "\nthis is not glsl;\n");
  live.poll();
  ASSERT_TRUE(live.error());
  EXPECT_EQ(fs::weakly_canonical(live.error()->file), fs::weakly_canonical(include)) << live.error()->summary();
  EXPECT_GT(live.error()->line, 0);
  write_text(include, text);
  EXPECT_TRUE(live.poll().shaders_reloaded);
  EXPECT_FALSE(live.error());
}

TEST_F(LiveRendererTest, BrokenSceneFileAndAssetKeepTheLastSceneThenReload) {
  LiveRenderer& live = start();
  const std::vector<float> before = render();
  const size_t meshes = live.scene().meshes.size();
  ASSERT_GT(meshes, 0u);

  write_text(scene_file(), "{ \"version\": 1, \"models\": [ ");
  PollResult bad_scene = live.poll();
  EXPECT_TRUE(bad_scene.failed);
  ASSERT_TRUE(live.error());
  EXPECT_EQ(live.error()->file.filename(), "scene.json");
  EXPECT_EQ(live.scene().meshes.size(), meshes);
  EXPECT_EQ(render(), before);

  // A truncated glTF: the error names the asset, the old meshes stay.
  write_text(scene_file(), kSceneJson);
  const fs::path gltf = root_ / "content/stage.gltf";
  const std::string gltf_text = read_text(gltf);
  write_text(gltf, gltf_text.substr(0, gltf_text.size() / 2));
  PollResult bad_asset = live.poll();
  EXPECT_TRUE(bad_asset.failed);
  ASSERT_TRUE(live.error());
  EXPECT_EQ(live.error()->file.filename(), "stage.gltf") << live.error()->summary();
  EXPECT_EQ(render(), before);

  // Both fixed, and the scene now moves the sun: the picture changes.
  write_text(gltf, gltf_text);
  std::string moved = kSceneJson;
  moved.replace(moved.find("[0.35, -1.0, 0.25]"), 18, "[-0.6, -1.0, 0.10]");
  write_text(scene_file(), moved);
  PollResult fixed = live.poll();
  EXPECT_TRUE(fixed.scene_reloaded);
  EXPECT_FALSE(live.error());
  EXPECT_NE(render(), before);
}

TEST_F(LiveRendererTest, BrokenVolumeKeepsTheSmokeThenReloads) {
  fs::copy_file(fs::path(AVSM_DEFAULT_SCENE).parent_path() / "plume.vdb", root_ / "content/plume.vdb");
  std::string with_smoke = kSceneJson;
  with_smoke.replace(with_smoke.find("\"lights\""), 0,
                     R"("volumes": [ { "name": "plume", "file": "plume.vdb", "grid": "density", "extinction_scale": 1.5,
                                     "transform": { "translation": [-1.3, 0.0, -0.4] } } ],
  )");
  write_text(scene_file(), with_smoke);
  LiveRenderer& live = start();
  ASSERT_EQ(live.scene().volumes.size(), 1u);
  const std::vector<float> before = render();

  // A VDB cut short: the loader's error names it, the smoke stays.
  const fs::path vdb = root_ / "content/plume.vdb";
  const std::string bytes = read_text(vdb);
  write_text(vdb, bytes.substr(0, bytes.size() / 3));
  EXPECT_TRUE(live.poll().failed);
  ASSERT_TRUE(live.error());
  EXPECT_EQ(live.error()->file.filename(), "plume.vdb") << live.error()->summary();
  EXPECT_EQ(live.scene().volumes.size(), 1u);
  EXPECT_EQ(render(), before);

  // Restored, and thinned by half in the scene file: reloads, the picture changes.
  write_text(vdb, bytes);
  std::string thinner = with_smoke;
  const std::string thick = "\"extinction_scale\": 1.5";
  thinner.replace(thinner.find(thick), thick.size(), "\"extinction_scale\": 0.5");
  write_text(scene_file(), thinner);
  EXPECT_TRUE(live.poll().scene_reloaded);
  EXPECT_FALSE(live.error()) << live.error()->summary();
  EXPECT_NE(render(), before);
}

TEST_F(LiveRendererTest, EditsApplyToEveryReloadAndBadEditsAreRejected) {
  LiveRenderer& live = start();
  live.set_scene_edit([](scene::Scene& scene) { scene.lights[0].shadow.nodes = 8; });
  EXPECT_TRUE(live.poll().scene_reloaded);
  EXPECT_EQ(live.renderer().shadows().light_views().size(), 1u);
  render();
  ASSERT_EQ(live.renderer().shadows().frame_stats().size(), 1u);
  EXPECT_EQ(live.renderer().shadows().frame_stats()[0].nodes, 8u);
  EXPECT_EQ(live.loaded_scene().lights[0].shadow.nodes, 4);

  // A node count the resolve cannot build: rejected, the AVSM-8 scene stays.
  live.set_scene_edit([](scene::Scene& scene) { scene.lights[0].shadow.nodes = 5; });
  EXPECT_TRUE(live.poll().failed);
  ASSERT_TRUE(live.error());
  EXPECT_TRUE(live.error()->file.empty());  // no file to blame
  EXPECT_EQ(live.error()->summary().rfind("edit: ", 0), 0u) << live.error()->summary();
  EXPECT_NE(live.error()->summary().find("5 AVSM nodes"), std::string::npos) << live.error()->summary();
  EXPECT_EQ(live.scene().lights[0].shadow.nodes, 8);
  render();
  EXPECT_EQ(live.renderer().shadows().frame_stats()[0].nodes, 8u);
}


// A volume sequence plays as the time moves: each frame read on the player's thread and
// shown once it is ready; a broken frame is reported by file and frame while the volume
// keeps the last good one, and playing on past it shows the next.
TEST_F(LiveRendererTest, SequenceFramesFollowTheTimeAndABrokenFrameKeepsTheLastGood) {
  const fs::path generated = fs::path(AVSM_DEFAULT_SCENE).parent_path() / "plume_sequence";
  fs::copy(generated, root_ / "content/plume_sequence", fs::copy_options::recursive);
  std::string scene = kSceneJson;
  scene.replace(scene.find("\"lights\""), 0, R"("volumes": [ { "file": "plume_sequence/plume.####.vdb", "grid": "density",
      "extinction_scale": 6, "transform": { "translation": [-0.4, 0.0, -0.4] } } ],
  )");
  write_text(scene_file(), scene);
  LiveRenderer& live = start();
  ASSERT_EQ(live.scene().volume_sequences.size(), 1u);
  const auto shows = [&](int frame) { return live.sequence_frame(0) == frame; };
  // Polls (the viewer's loop) until `done`, for at most 20 s.
  const auto poll_until = [&](const std::function<bool()>& done) {
    for (int tries = 0; tries < 400 && !done(); ++tries) {
      std::this_thread::sleep_for(std::chrono::milliseconds(50));
      live.poll(Clock::now());
    }
    return done();
  };
  EXPECT_TRUE(shows(1));  // the time's own, waited for at load
  const std::vector<float> frame_1 = render();

  live.set_time(10.0f / 24.0f);  // frame 11
  ASSERT_TRUE(poll_until([&] { return shows(11); }));
  const std::vector<float> frame_11 = render();
  EXPECT_NE(frame_11, frame_1);
  EXPECT_FALSE(live.error().has_value());

  fs::resize_file(root_ / "content/plume_sequence/plume.0016.vdb", 1000);
  live.set_time(15.0f / 24.0f);  // frame 16
  ASSERT_TRUE(poll_until([&] { return live.error().has_value(); }));
  EXPECT_EQ(fs::weakly_canonical(live.error()->file), fs::weakly_canonical(root_ / "content/plume_sequence/plume.0016.vdb"));
  EXPECT_NE(live.error()->summary().find("frame 16 of the sequence"), std::string::npos) << live.error()->summary();
  EXPECT_TRUE(shows(11));
  EXPECT_EQ(render(), frame_11);  // the last good frame stays

  live.set_time(20.0f / 24.0f);  // frame 21
  ASSERT_TRUE(poll_until([&] { return shows(21); }));
  EXPECT_FALSE(live.error().has_value());
  EXPECT_NE(render(), frame_11);
}

// ---- Saving the way editors do ---------------------------------------------------
// The scene file, an asset (the stage's glTF) and a shader are saved in each way
// editors do, polling at the moments that matter with time driven by the test. While a
// file is incomplete or missing, the last good content keeps rendering and nothing is
// reported; once it settles, its final content is what gets loaded, in one reload.

constexpr SettleTimes kEditorSettle{std::chrono::milliseconds(150), std::chrono::milliseconds(2000)};

// One file an editor saves over and over: version 0 is the file the test starts from,
// versions 1 to 14 each render differently, and expect_loaded() checks which one is in use.
struct EditedFile {
  std::string kind;
  fs::path file;
  std::function<std::string(int)> version;
  std::function<void(int)> expect_loaded;
};

std::string fixed2(double value) {
  char text[32];
  std::snprintf(text, sizeof(text), "%.2f", value);
  return text;
}

std::string replaced(std::string text, const std::string& from, const std::string& to) {
  const size_t at = text.find(from);
  if (at == std::string::npos) throw std::logic_error(from + " not found");
  return text.replace(at, from.size(), to);
}

// An editor that writes a temporary file beside the original and renames it over.
void save_by_rename(const fs::path& file, const std::string& text) {
  fs::path temporary = file;
  temporary += ".saving";
  std::ofstream(temporary, std::ios::trunc) << text;
  fs::rename(temporary, file);
}

class EditorSaveTest : public LiveRendererTest {
 protected:
  LiveRenderer& start_watching() {
    LiveRenderer& live = start(kEditorSettle);
    shown_ = render();
    return live;
  }

  PollResult poll_after(Clock::duration elapsed) { return live_->poll(now_ += elapsed); }
  PollResult poll_after_settling() { return poll_after(kEditorSettle.settle); }

  // The scene file (the sun's direction), the stage's glTF (the box's position) and
  // the tonemap shader (blue set to a constant, larger with each version, so that the
  // other edits still show).
  std::vector<EditedFile> edited_files() {
    const std::string scene = kSceneJson;
    const fs::path gltf = root_ / "content/stage.gltf";
    const std::string stage = read_text(gltf);
    const fs::path tonemap = shader("passes/camera/tonemap.comp");
    const std::string tonemapper = read_text(tonemap);
    return {
        {"scene file", scene_file(),
         [=](int v) { return replaced(scene, "[0.35, -1.0, 0.25]", "[" + fixed2(0.35 - 0.07 * v) + ", -1.0, 0.25]"); },
         [this](int v) {
           const glm::vec3 d = live_->scene().lights.at(0).direction;
           EXPECT_NEAR(d.x / -d.y, 0.35 - 0.07 * v, 1e-4) << "sun direction of version " << v;
         }},
        {"asset", gltf, [=](int v) { return replaced(stage, "    1.9,\n", "    " + fixed2(1.9 - 0.1 * v) + ",\n"); },
         [this](int v) {
           const auto box = std::find_if(live_->scene().meshes.begin(), live_->scene().meshes.end(),
                                         [](const scene::Mesh& m) { return m.name == "stage/box"; });
           ASSERT_NE(box, live_->scene().meshes.end());
           EXPECT_NEAR((box->bounds.min.x + box->bounds.max.x) / 2, 1.9 - 0.1 * v, 1e-3) << "box of version " << v;
         }},
        {"shader", tonemap,
         [=](int v) {
           return replaced(tonemapper, "vec3 mapped = filmic(c);",
                           "vec3 mapped = filmic(c); mapped.b = " + fixed2(v / 20.0) + ";");
         },
         [this](int v) {
           const float linear = v / 20.0f;
           const float srgb = 1.055f * std::pow(linear, 1.0f / 2.4f) - 0.055f;
           const std::vector<float> rgba = render();
           for (size_t blue = 2; blue < rgba.size(); blue += 4)
             ASSERT_NEAR(rgba[blue], srgb, 1.5f / 255) << "tonemap of version " << v << ", value " << blue;
         }},
    };
  }

  // Mid-save: nothing reloads or is reported, and the last good picture stays.
  void expect_last_good_kept(const PollResult& poll, const std::string& when) {
    SCOPED_TRACE(when);
    EXPECT_FALSE(poll.anything_new());
    EXPECT_FALSE(poll.failed);
    EXPECT_TRUE(poll.waiting);
    EXPECT_FALSE(live_->error()) << live_->error()->summary();
    EXPECT_EQ(render(), shown_);
  }
  // Settled: one reload, of the final content.
  void expect_reloaded(const PollResult& poll, const EditedFile& edited, int version) {
    EXPECT_TRUE(poll.anything_new());
    EXPECT_FALSE(poll.waiting);
    EXPECT_FALSE(live_->error()) << live_->error()->summary();
    edited.expect_loaded(version);
    const std::vector<float> now_shown = render();
    EXPECT_NE(now_shown, shown_);
    shown_ = now_shown;
  }

  std::vector<float> shown_;  // the picture of the last good content
  Clock::time_point now_ = Clock::now();
};

// The four ways of saving, each on the scene file, the asset and the shader; one
// LiveRenderer for all (starting one compiles every shader: the costly part).
TEST_F(EditorSaveTest, EditorsWaysOfSavingKeepTheLastGoodContentThenLoadTheFinalOne) {
  start_watching();
  const std::vector<EditedFile> files = edited_files();
  for (const EditedFile& edited : files) {
    SCOPED_TRACE(edited.kind + ", renamed over");
    save_by_rename(edited.file, edited.version(1));
    expect_last_good_kept(poll_after(Clock::duration(0)), "just renamed over");
    expect_reloaded(poll_after_settling(), edited, 1);
  }
  for (const EditedFile& edited : files) {
    SCOPED_TRACE(edited.kind + ", truncated then written in chunks");
    const std::string text = edited.version(2);
    const size_t third = text.size() / 3;
    std::ofstream out(edited.file, std::ios::trunc);
    expect_last_good_kept(poll_after(Clock::duration(0)), "truncated");
    out << text.substr(0, third) << std::flush;
    expect_last_good_kept(poll_after(std::chrono::milliseconds(50)), "first chunk");
    // The editor stalls past the settle time, and its second chunk lands while the
    // reload reads: the half-written file is read, and dropped, not reported.
    during_read_ = [&] { out << text.substr(third, third) << std::flush; };
    expect_last_good_kept(poll_after_settling(), "read during the second chunk");
    EXPECT_FALSE(during_read_) << "no reload read the file";
    out << text.substr(2 * third);
    out.close();
    expect_last_good_kept(poll_after(std::chrono::milliseconds(50)), "last chunk written");
    expect_reloaded(poll_after_settling(), edited, 2);
  }
  for (const EditedFile& edited : files) {
    SCOPED_TRACE(edited.kind + ", deleted then recreated");
    fs::remove(edited.file);
    expect_last_good_kept(poll_after(Clock::duration(0)), "deleted");
    expect_last_good_kept(poll_after(std::chrono::milliseconds(1000)), "still missing");
    std::ofstream(edited.file, std::ios::trunc) << edited.version(3);
    expect_last_good_kept(poll_after(Clock::duration(0)), "recreated");
    expect_reloaded(poll_after_settling(), edited, 3);

    // Gone for longer than the grace: reported, naming the file; the picture stays.
    fs::remove(edited.file);
    expect_last_good_kept(poll_after(Clock::duration(0)), "deleted again");
    const PollResult gone = poll_after(kEditorSettle.missing);
    EXPECT_TRUE(gone.failed);
    ASSERT_TRUE(live_->error());
    EXPECT_EQ(live_->error()->file.filename(), edited.file.filename()) << live_->error()->summary();
    EXPECT_EQ(render(), shown_);
    std::ofstream(edited.file, std::ios::trunc) << edited.version(4);
    poll_after(Clock::duration(0));
    expect_reloaded(poll_after_settling(), edited, 4);
  }
  for (const EditedFile& edited : files) {
    SCOPED_TRACE(edited.kind + ", ten saves within 50 ms");
    for (int version = 5; version <= 14; ++version) {
      std::ofstream(edited.file, std::ios::trunc) << edited.version(version);
      expect_last_good_kept(poll_after(std::chrono::milliseconds(5)), "version " + std::to_string(version));
    }
    expect_reloaded(poll_after_settling(), edited, 14);
  }
}

}  // namespace
}  // namespace live_renderer_test
}  // namespace avsm::live
