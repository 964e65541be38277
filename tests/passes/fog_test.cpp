// The fog (scene/fog.h, passes/camera/fog/): off, it leaves every pixel as it was; a
// uniform fog under an unshadowed sun gives the closed form on the background; and the
// froxel grid's fog over the default scene, shafts and all, matches the per-pixel march
// with every light's map looked up at each step.
#include <gtest/gtest.h>

#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <cmath>
#include <filesystem>
#include <iostream>
#include <vector>

#include "passes/shadows/shadow_settings.h"
#include "capture/fog_comparison.h"
#include "gpu/transfer.h"
#include "passes/frame/view.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"
#include "support/gpu_test.h"

namespace avsm {
namespace fog_test {  // one per file: test targets are unity builds
namespace {

// The comparison with the march needs a grid of some size; the other tests a small frame.
constexpr uint32_t kWidth = 192, kHeight = 108;
constexpr uint32_t kSmallWidth = 96, kSmallHeight = 54;

struct FogSwitches {
  bool enabled = true;
  std::optional<bool> per_pixel;
  uint32_t width = kSmallWidth, height = kSmallHeight;
  int frames = 2;  // the second frame has capture buffers that fit
  passes::ShadowOptions shadows;
  std::vector<passes::LightShadowStats>* shadow_stats = nullptr;  // the last frame's, when given
};

class FogTest : public testing::GpuTest {
 protected:
  gpu::ImageRGBA32F render(const scene::Scene& scene, FogSwitches switches = {}) {
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, switches.width, switches.height, switches.shadows);
    renderer.set_fog_enabled(switches.enabled);
    renderer.set_fog_marched_per_pixel(switches.per_pixel);
    rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
    const passes::View view = passes::make_view(scene.cameras.front(), switches.width, switches.height);
    for (int frame = 0; frame < switches.frames; ++frame) {
      rg::Graph graph = renderer.build_frame(view);
      ctx().submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
      renderer.finish_frame();
    }
    if (switches.shadow_stats) *switches.shadow_stats = renderer.shadows().frame_stats();
    return gpu::read_image(ctx(), renderer.hdr(), renderer::SceneRenderer::kOutputLayout);
  }
};

// With dense maps of its lights' resolution (its own are paged, and take more than the
// two frames render() draws to be finished), as --shadow-res gives.
scene::Scene default_scene() {
  scene::Scene scene = scene::load_scene(AVSM_DEFAULT_SCENE);
  for (scene::Light& light : scene.lights) passes::apply_shadow_overrides({.resolution = light.shadow.resolution}, light);
  return scene;
}

// A low ground fog over a thin global one, lit forward: the sun's and the spot's shafts
// through the plume, the curtain and the stage's meshes.
scene::Fog ground_fog() {
  scene::Fog fog;
  fog.global = {.scattering = 0.05f, .absorption = 0.01f, .color = glm::vec3(1.0f), .phase_g = 0.5f};
  scene::FogBox box;
  box.bounds.min = glm::vec3(-6.0f, 0.0f, -4.0f);
  box.bounds.max = glm::vec3(6.0f, 0.8f, 4.0f);
  box.medium = {.scattering = 0.3f, .absorption = 0.0f, .color = glm::vec3(0.9f, 0.95f, 1.0f), .phase_g = 0.2f};
  fog.boxes.push_back(box);
  return fog;
}

bool same_pixels(const gpu::ImageRGBA32F& a, const gpu::ImageRGBA32F& b) { return a.pixels == b.pixels; }

float henyey_greenstein(float cos_theta, float g) {
  const float d = 1.0f + g * g - 2.0f * g * cos_theta;
  return (1.0f - g * g) / (4.0f * 3.14159265f * d * std::sqrt(d));
}

}  // namespace

// Fog switched off leaves every pixel (smoke and hair composites included) as a scene
// without fog renders it.
TEST_F(FogTest, OffOrEmptyLeavesTheFrameBitForBit) {
  const scene::Scene plain = default_scene();
  const gpu::ImageRGBA32F without = render(plain);
  scene::Scene fogged = plain;
  fogged.fog = ground_fog();
  EXPECT_TRUE(same_pixels(render(fogged, {.enabled = false}), without)) << "switched off";
  EXPECT_FALSE(same_pixels(render(fogged), without)) << "not vacuous: the fog shows";
}

// The sun alone over a uniform fog (coloured, forward-scattering): along a background
// ray above the stage nothing shadows the sun, so the fog there is the closed form
// B T + sigma_s colour (L_sun HG(cos) + sky) (1 - T) / sigma_t, T = exp(-sigma_t d), d the
// fog's distance. Both the froxel grid and the per-pixel march must give it.
TEST_F(FogTest, AUniformFogUnderTheSunIsTheClosedFormOnTheBackground) {
  scene::Scene scene = default_scene();
  scene.lights.resize(1);  // the sun
  // Nothing to shadow the fog: the floor alone, below every ray looked at.
  scene.hair.clear();
  scene.volumes.clear();
  std::erase_if(scene.meshes, [](const scene::Mesh& mesh) { return mesh.bounds.max.y > 0.05f; });
  ASSERT_FALSE(scene.meshes.empty()) << "the stage has a floor";
  const scene::Scene plain = scene;
  scene::Fog& fog = scene.fog;
  fog.global = {.scattering = 0.08f, .absorption = 0.02f, .color = glm::vec3(1.0f, 0.8f, 0.6f), .phase_g = 0.6f};
  fog.grid.distance = 12.0f;
  fog.grid.froxel_pixels = 8;
  fog.sky_light = 0.5f;
  const gpu::ImageRGBA32F background = render(plain);
  const passes::View view = passes::make_view(scene.cameras.front(), kSmallWidth, kSmallHeight);
  const scene::Light& sun = scene.lights[0];
  const float extinction = fog.global.scattering + fog.global.absorption;
  const float transmittance = std::exp(-extinction * fog.grid.distance);
  const glm::vec3 sky(0.08f, 0.1f, 0.14f);  // kSkyAmbient (shared/lights.h)
  for (const bool per_pixel : {false, true}) {
    const gpu::ImageRGBA32F fogged = render(scene, {.per_pixel = per_pixel});
    double largest = 0.0;
    // A row near the top, sky above the stage, between the first two rows of froxel
    // centres (the grid interpolates the phase function's change across the view there;
    // in the outer half froxel it holds the outermost centre's).
    constexpr uint32_t kRow = 8;
    for (uint32_t x = 12; x + 12 < kSmallWidth; x += 12) {
      const glm::vec3 direction = passes::pixel_ray(view, glm::vec2(x, kRow)).direction;  // through its centre
      const glm::vec3 light = sun.color * sun.intensity;
      const glm::vec3 scattered = fog.global.scattering * fog.global.color *
                                  (light * henyey_greenstein(glm::dot(-sun.direction, direction), fog.global.phase_g) +
                                   sky * fog.sky_light) * ((1.0f - transmittance) / extinction);
      const float* b = background.at(x, kRow);
      const float* f = fogged.at(x, kRow);
      for (int c = 0; c < 3; ++c) {
        const double expected = b[c] * transmittance + scattered[c];
        largest = std::max(largest, std::abs(f[c] - expected) / expected);
      }
    }
    std::cout << "[ fog closed form ] " << (per_pixel ? "per-pixel march" : "froxel grid")
              << ": largest relative error on the background " << largest << "\n";
    EXPECT_LT(largest, 0.01) << (per_pixel ? "per-pixel march" : "froxel grid");
  }
}

// The default scene under a ground fog, both lights shadowed by the plume, the curtain and
// the stage: the froxel grid's fog against the per-pixel march, as relative L1 of the fog's
// effect (capture::compare_fog, the bound of avsm-capture --compare-fog). The smoke is hidden from the camera (it still casts), so that
// only the fog differs.
TEST_F(FogTest, TheFroxelGridMatchesThePerPixelMarch) {
  scene::Scene scene = default_scene();
  scene.volume_shading.mode = scene::VolumeShading::Mode::hidden;
  const FogSwitches large{.width = kWidth, .height = kHeight};
  const gpu::ImageRGBA32F plain = render(scene, large);
  scene.fog = ground_fog();
  // Froxels of 8 pixels: the grid this small frame gets is then 24 x 14 columns, as a
  // 1280x720 frame's is 80 x 45 at the default 16.
  scene.fog.grid.froxel_pixels = 8;
  const gpu::ImageRGBA32F reference = render(scene, {.per_pixel = true, .width = kWidth, .height = kHeight});
  const gpu::ImageRGBA32F fast = render(scene, {.per_pixel = false, .width = kWidth, .height = kHeight});
  const capture::FogComparison comparison = capture::compare_fog(fast, reference, plain);
  ASSERT_GT(comparison.fogged_pixels, kWidth * kHeight / 2) << "the fog must show over most of the frame";
  std::cout << "[ fog vs march ] " << comparison.fogged_pixels << " fogged pixels, relative L1 of the fog's effect "
            << comparison.relative_l1() << "\n";
  EXPECT_TRUE(comparison.within_bound()) << comparison.relative_l1();
}

// The ground fog under paged lights whose receivers all read the level that is a dense
// 128^2 map (a 512^2 virtual map in pages of 32, shadow.resolution 128, a page bias of 8):
// the froxels ask for the pages they read, find them, and the frame, fog and all, is the
// dense maps' frame. Pages of that level equal the dense map bit for bit
// (PagedMapsTest.OneForcedLevelWithEveryPageResidentIsTheDenseMapBitForBit).
TEST_F(FogTest, PagedLightsHeldAtTheDenseLevelGiveTheDenseFrame) {
  scene::Scene dense = default_scene();
  for (scene::Light& light : dense.lights) {
    passes::apply_shadow_overrides({.resolution = 128}, light);
    light.shadow.kernel = scene::ShadowKernel::none;
    light.shadow.filter = scene::ShadowFilter::bilinear;
  }
  dense.fog = ground_fog();
  scene::Scene paged = dense;
  for (scene::Light& light : paged.lights) {
    light.shadow.layout = scene::ShadowLayout::paged;
    light.shadow.virtual_resolution = 512;
    light.shadow.page_size = 32;
    light.shadow.page_lod_bias = 8.0f;
    light.shadow.page_pool_mib = 1.0;  // 32 slots of AVSM-8: the 21 pages of level 2 and above
  }
  const gpu::ImageRGBA32F expected = render(dense);
  std::vector<passes::LightShadowStats> stats;
  const gpu::ImageRGBA32F fogged =
      render(paged, {.frames = 3, .shadows = {.unlimited_page_builds = true}, .shadow_stats = &stats});
  for (size_t light = 0; light < paged.lights.size(); ++light) {
    ASSERT_TRUE(stats.at(light).pages) << paged.lights[light].name << " is paged";
    EXPECT_EQ(stats[light].pages->pending, 0u) << paged.lights[light].name;
    EXPECT_GE(stats[light].pages->resident, 16u) << paged.lights[light].name << ": level 2 is 16 pages";
  }
  EXPECT_TRUE(same_pixels(fogged, expected)) << "the paged frame differs from the dense maps' frame";
  dense.fog = {};
  EXPECT_FALSE(same_pixels(render(dense), expected)) << "not vacuous: the fog shows";
}

// Opaque hair in front of a far background, in a uniform fog lit by the sky alone (no
// lights, no smoke), so the fog over a pixel of colour c at distance d is
// c T + S_inf (1 - T), T = exp(-sigma_t d), S_inf = sigma_s sky / sigma_t. Solving each pixel
// for d shows where the frame fogged it: the hair at the hair's distance (per strand vertex,
// in front of what lies behind it), the background behind it farther.
TEST_F(FogTest, HairIsFoggedAtItsOwnDistance) {
  scene::Scene scene = scene::load_scene(std::filesystem::path(AVSM_DEFAULT_SCENE).parent_path() /
                                         "hair_in_front_of_smoke.scene.json");
  scene.lights.clear();
  scene.volume_shading.mode = scene::VolumeShading::Mode::hidden;
  scene::HairGroom& groom = scene.hair.at(0);
  for (float& opacity : groom.strand_opacity) opacity = 1.0f;
  for (float& width : groom.strand_width) width *= 40.0f;  // a pixel covered sees one strand only
  scene::Scene bare = scene;
  bare.hair.clear();
  scene::Fog fog;
  fog.global = {.scattering = 0.3f, .absorption = 0.0f, .color = glm::vec3(1.0f), .phase_g = 0.0f};
  fog.grid.distance = 30.0f;
  const gpu::ImageRGBA32F hair = render(scene), background = render(bare);
  scene.fog = fog;
  bare.fog = fog;
  const gpu::ImageRGBA32F fogged_hair = render(scene), fogged_background = render(bare);
  const glm::vec3 far_fog(0.08f, 0.1f, 0.14f);  // S_inf: kSkyAmbient (shared/lights.h), sigma_s = sigma_t
  // The distance the fog over a pixel went to, from its blue channel (farthest from S_inf).
  auto fogged_distance = [&](const float* clear, const float* fogged) {
    const float transmittance = (fogged[2] - far_fog.z) / (clear[2] - far_fog.z);
    return -std::log(std::clamp(transmittance, 1e-6f, 1.0f)) / fog.global.scattering;
  };
  float nearest = 1e9f, farthest = 0.0f;  // the groom's distances from the camera
  for (int c = 0; c < 8; ++c) {
    const float d = glm::length(groom.bounds.corner(c) - scene.cameras[0].position);
    nearest = std::min(nearest, d), farthest = std::max(farthest, d);
  }
  std::vector<float> hair_distances, background_distances;
  for (uint32_t y = 0; y < kSmallHeight; ++y)
    for (uint32_t x = 0; x < kSmallWidth; ++x) {
      const float* h = hair.at(x, y);
      const float* b = background.at(x, y);
      if (std::abs(h[2] - b[2]) < 0.05f) continue;  // not covered by a strand
      hair_distances.push_back(fogged_distance(h, fogged_hair.at(x, y)));
      background_distances.push_back(fogged_distance(b, fogged_background.at(x, y)));
    }
  ASSERT_GT(hair_distances.size(), 200u) << "the curtain covers the frame's middle";
  auto median = [](std::vector<float> v) {
    std::nth_element(v.begin(), v.begin() + ptrdiff_t(v.size() / 2), v.end());
    return v[v.size() / 2];
  };
  const float hair_median = median(hair_distances), background_median = median(background_distances);
  std::cout << "[ hair in fog  ] " << hair_distances.size() << " hair pixels fogged at a median " << hair_median
            << " m (the groom lies " << nearest << " to " << farthest << " m away), the background behind at "
            << background_median << " m\n";
  EXPECT_GT(hair_median, nearest - 0.1f);
  EXPECT_LT(hair_median, farthest + 0.1f);
  EXPECT_GT(background_median, farthest + 1.0f) << "not vacuous: the background lies well behind the hair";
}

// A grid larger than a shader binding can see (maxStorageBufferRange: 128 MiB on lavapipe)
// is an error that names the settings to change, before anything is recorded.
TEST_F(FogTest, AGridTheDeviceCannotBindIsAnErrorNamingItsSettings) {
  scene::Scene scene = default_scene();
  scene.fog = ground_fog();
  scene.fog.grid.froxel_pixels = 4;
  scene.fog.grid.slices = 256;  // 320 x 180 x 256 froxels at 1280x720: 225 MiB
  renderer::SceneRenderer renderer(ctx(), shaders(), scene, 1280, 720);
  try {
    renderer.build_frame(passes::make_view(scene.cameras.front(), 1280, 720));
    ADD_FAILURE() << "accepted";
  } catch (const std::exception& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find("'fog integrated"), std::string::npos) << message;
    EXPECT_NE(message.find("lower the fog's slices or the image size (or raise its froxel_pixels)"), std::string::npos)
        << message;
  }
}

}  // namespace fog_test
}  // namespace avsm
