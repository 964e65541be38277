// Hair and smoke in depth order (SceneRenderer, fast and reference volume shading):
// strands in front of smoke are not darkened by the smoke behind them.
#include <gtest/gtest.h>

#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <vector>

#include "capture/volume_comparison.h"
#include "gpu/transfer.h"
#include "passes/frame/view.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"
#include "support/gpu_test.h"
#include "support/test_volumes.h"

namespace avsm {
namespace volume_shading_test {  // one per file: test targets are unity builds
namespace {

using Mode = scene::VolumeShading::Mode;
constexpr uint32_t kWidth = 160, kHeight = 90;

double luminance(const float* rgba) { return 0.2126 * rgba[0] + 0.7152 * rgba[1] + 0.0722 * rgba[2]; }

class VolumeShadingTest : public testing::GpuTest {
 protected:
  // The test scene with its strands made opaque and wide, so a covered pixel shows
  // the front-most strand only; `hair` false: strands fully transparent.
  static scene::Scene curtain_scene(bool hair) {
    scene::Scene scene = scene::load_scene(std::filesystem::path(AVSM_DEFAULT_SCENE).parent_path() /
                                           "hair_in_front_of_smoke.scene.json");
    for (scene::HairGroom& groom : scene.hair) {
      for (float& opacity : groom.strand_opacity) opacity = hair ? 1.0f : 0.0f;
      for (float& width : groom.strand_width) width *= 40.0f;
    }
    return scene;
  }

  gpu::ImageRGBA32F render(Mode mode, bool hair) { return render(curtain_scene(hair), mode); }

  gpu::ImageRGBA32F render(scene::Scene scene, Mode mode) {
    scene.volume_shading.mode = mode;
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, kWidth, kHeight);
    // Opaque strands shadow each other all or nothing, so per-vertex and per-fragment
    // lighting differ there; this test is about the compositing, so both light per fragment.
    renderer.set_hair_lighting_per_fragment(true);
    rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
    const passes::View view = passes::make_view(scene.cameras.front(), kWidth, kHeight);
    for (int frame = 0; frame < 2; ++frame) {  // the second frame has capture buffers that fit
      rg::Graph graph = renderer.build_frame(view);
      ctx().submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
      renderer.finish_frame();
    }
    return gpu::read_image(ctx(), renderer.hdr(), renderer::SceneRenderer::kOutputLayout);
  }
};

// Whether the frame's hair pass looks shadows up itself (per fragment: the frame's shadow
// records among its reads) rather than reading what the per-vertex lighting pass wrote.
bool hair_lit_per_fragment(const rg::Graph& graph) {
  for (const rg::PassDecl& pass : graph.passes()) {
    if (pass.name != "hair") continue;
    for (const rg::AccessDecl& access : pass.accesses)
      if (graph.resources()[access.resource].name == "shadow parameters") return true;
    return false;
  }
  ADD_FAILURE() << "the frame has no hair pass";
  return false;
}

// Hair is lit per fragment (every light's shadow lookups in every fragment) in the
// reference volume shading only: with the volumes hidden it keeps the fast per-vertex
// lighting, which per fragment was 18x slower at 1280x720 (930 against 52 ms).
TEST_F(VolumeShadingTest, HairIsLitPerFragmentInTheReferenceShadingOnly) {
  for (Mode mode : {Mode::fast, Mode::hidden, Mode::reference}) {
    scene::Scene scene = curtain_scene(true);
    scene.volume_shading.mode = mode;
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, kWidth, kHeight);
    const rg::Graph graph = renderer.build_frame(passes::make_view(scene.cameras.front(), kWidth, kHeight));
    EXPECT_EQ(hair_lit_per_fragment(graph), mode == Mode::reference) << scene::to_string(mode);
  }
}

TEST_F(VolumeShadingTest, HairInFrontOfSmokeIsNotDarkenedBySmokeBehindIt) {
  const gpu::ImageRGBA32F smoke_no_hair = render(Mode::reference, false);
  const gpu::ImageRGBA32F no_smoke_no_hair = render(Mode::hidden, false);
  const gpu::ImageRGBA32F no_smoke = render(Mode::hidden, true);
  for (Mode mode : {Mode::reference, Mode::fast}) {
    const gpu::ImageRGBA32F both = render(mode, true);
    // Pixels where the smoke shows without hair and opaque hair covers it.
    double smoke_change = 0.0, hair_error = 0.0;
    int pixels = 0;
    for (uint32_t y = 0; y < kHeight; ++y)
      for (uint32_t x = 0; x < kWidth; ++x) {
        const double background = luminance(no_smoke_no_hair.at(x, y));
        const double smoke = std::abs(luminance(smoke_no_hair.at(x, y)) - background) / background;
        const double hair_only = luminance(no_smoke.at(x, y));
        if (smoke < 0.05 || std::abs(hair_only - background) < 0.2 * background) continue;
        smoke_change += smoke;
        hair_error += std::abs(luminance(both.at(x, y)) - hair_only) / hair_only;
        ++pixels;
      }
    ASSERT_GT(pixels, 100) << "the curtain must cover smoke";
    // The smoke behind changes those pixels by this much without the hair, so hair
    // composited under it (the old order) would be off by about as much.
    EXPECT_GT(smoke_change / pixels, 0.1) << scene::to_string(mode);
    EXPECT_LT(hair_error / pixels, 0.01) << scene::to_string(mode);
  }
}

// A dense, bright box of smoke (optical depth 4.8 across, albedo 0.9) under a sun and
// the sky: nothing but the volume, so its CPU path tracing (every order of scattering)
// is the truth the renderer's octaves and sky term are measured against.
scene::Scene bright_box_scene() {
  scene::VolumeOptions options;
  options.extinction_scale = 2.0f;
  options.albedo = glm::vec3(0.9f);
  scene::Scene scene;
  scene.volumes.push_back(testing::load_box_volume({{glm::ivec3(0), glm::ivec3(23), 1.0f}}, 0.1f, options));
  scene.bounds = scene.volumes.back().world_bounds;
  scene::Light sun;
  sun.name = "sun";
  sun.direction = glm::normalize(glm::vec3(0.4f, -1.0f, -0.5f));
  sun.intensity = 3.0f;
  sun.shadow.resolution = 128;
  scene.lights.push_back(sun);
  scene::Camera camera;
  camera.target = scene.bounds.center();
  camera.position = camera.target + glm::vec3(1.5f, 1.0f, 6.0f);
  camera.vertical_fov = glm::radians(40.0f);
  scene.cameras.push_back(camera);
  return scene;
}

// Mean luminance of the smoke, each way, against the path-traced frame's: the octaves of
// multiple scattering and the sky's light bring the fast and reference shading within
// 10% of it; single scattering alone is far darker.
TEST_F(VolumeShadingTest, MultipleScatteringAndSkyLightMatchAPathTracedBox) {
  constexpr int kPaths = 16;  // the means run over some 3,400 pixels: noise well under 1%
  // The frame without the box, and the box path traced over it (the octaves do not change it).
  auto truth = [&](const scene::Scene& scene) {
    const gpu::ImageRGBA32F hidden = render(scene, Mode::hidden);
    const passes::View view = passes::make_view(scene.cameras.front(), kWidth, kHeight);
    return std::pair{hidden, capture::path_trace_volumes(scene, view, hidden, kPaths)};
  };
  const scene::Scene lit = bright_box_scene();
  scene::Scene single = lit, sky_only = lit;
  single.volumes.front().multiple_scattering.octaves = 1;
  sky_only.lights.clear();
  const auto [hidden, traced] = truth(lit);
  const capture::PathTracedComparison octaves =
      capture::compare_with_path_traced(render(lit, Mode::fast), render(lit, Mode::reference), hidden, traced, kPaths);
  const gpu::ImageRGBA32F single_fast = render(single, Mode::fast);
  const capture::PathTracedComparison single_scattering =
      capture::compare_with_path_traced(single_fast, single_fast, hidden, traced, kPaths);
  const auto [sky_hidden, sky_traced] = truth(sky_only);
  const gpu::ImageRGBA32F sky_fast = render(sky_only, Mode::fast);
  const capture::PathTracedComparison sky = capture::compare_with_path_traced(sky_fast, sky_fast, sky_hidden,
                                                                             sky_traced, kPaths);
  for (const auto& [name, c] : {std::pair{"4 octaves", octaves}, std::pair{"single scattering", single_scattering},
                                std::pair{"sky only, 4 octaves", sky}})
    std::cout << "[ path traced ] " << name << ": smoke luminance fast " << c.fast_luminance << ", path traced "
              << c.path_traced_luminance << " over " << c.smoke_pixels << " pixels\n";
  ASSERT_GT(octaves.smoke_pixels, uint64_t(kWidth * kHeight / 8));
  EXPECT_NEAR(octaves.fast_relative(), 0.0, 0.10);
  EXPECT_NEAR(octaves.reference_luminance / octaves.path_traced_luminance, 1.0, 0.10) << "the reference shading";
  EXPECT_LT(single_scattering.fast_relative(), -0.25) << "single scattering should miss much of the light";
  EXPECT_NEAR(sky.fast_relative(), 0.0, 0.10) << "the sky alone";
}

}  // namespace
}  // namespace volume_shading_test
}  // namespace avsm
