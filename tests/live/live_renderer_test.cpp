// Hot reload through LiveRenderer: broken shaders, scene files and assets keep
// the last good content rendering and report the file (and line) at fault; the
// fixed files load again. Works on a private copy of shaders/ and of the default
// scene's stage, so the edits never touch the repository.
#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>
#include <filesystem>
#include <fstream>
#include <sstream>
#include <string>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "gpu/vk_check.h"
#include "live/live_renderer.h"
#include "passes/view.h"
#include "rendergraph/vulkan/executor.h"
#include "support/gpu_test.h"

namespace avsm::live {
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
    // The shadow techniques' lookups, which the shaders include (passes/techniques/<name>/<name>.glsl).
    fs::create_directories(root_ / "passes");
    fs::copy(fs::path(AVSM_SOURCE_ROOT) / "passes/techniques", root_ / "passes/techniques", fs::copy_options::recursive);
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

  LiveRenderer& start() {
    LiveOptions options;
    options.scene_file = scene_file();
    options.width = 48;
    options.height = 32;
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
  EXPECT_TRUE(watches(shader("passes/tonemap.comp")));
  EXPECT_TRUE(watches(shader("common/shadow_lookup.glsl")));
}

TEST_F(LiveRendererTest, BrokenShaderKeepsTheLastPipelineAndFixedShaderSwapsIn) {
  LiveRenderer& live = start();
  const std::vector<float> before = render();
  renderer::SceneRenderer* const good_renderer = &live.renderer();

  // A syntax error: the old pipelines keep rendering the same picture.
  const fs::path tonemap = shader("passes/tonemap.comp");
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

}  // namespace
}  // namespace avsm::live
