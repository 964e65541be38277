// Paged transmittance maps (shadow.layout "paged"; passes/shadows/pages/): pages built
// over their windows of the virtual map equal the dense map of their level bit for bit,
// camera receivers ask for pages until the map converges, and a pool of a few pages
// serves every receiver from coarser levels and says so.
#include <gtest/gtest.h>
#include <rendergraph/rendergraph.h>
#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <cstring>
#include <iostream>
#include <sstream>
#include <vector>

#include "gpu/context.h"
#include "gpu/transfer.h"
#include "passes/frame/view.h"
#include "passes/shadows/pages/page_table.h"
#include "passes/shadows/shadow_maps.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"
#include "shared/pages.h"
#include "support/gpu_test.h"

namespace avsm {
namespace paged_maps_test {  // one per file: test targets are unity builds
namespace {

using PagedMapsTest = testing::GpuTest;

constexpr uint32_t kFrameWidth = 96, kFrameHeight = 54;

// The default scene's two lights (a directional sun fitted to the scene, a spot), AVSM
// (8 nodes unless told) bilinear without mips or kernel, in `layout`.
scene::Scene default_scene(scene::ShadowLayout layout, int resolution, int nodes = 8) {
  scene::Scene scene = scene::load_scene(AVSM_DEFAULT_SCENE);
  for (scene::Light& light : scene.lights) {
    scene::ShadowSettings& s = light.shadow;
    s.technique = "avsm";
    s.nodes = nodes;
    s.resolution = resolution;
    s.filter = scene::ShadowFilter::bilinear;
    s.kernel = scene::ShadowKernel::none;
    s.fit = scene::ShadowFit::scene;
    s.layout = layout;
  }
  return scene;
}

void render_frames(gpu::Context& ctx, renderer::SceneRenderer& renderer, const passes::View& view, int frames) {
  rg::vulkan::Executor executor(ctx, gpu::TimestampMode::Exact);
  for (int i = 0; i < frames; ++i) {
    rg::Graph graph = renderer.build_frame(view);
    ctx.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
    renderer.finish_frame();
  }
}

std::vector<uint32_t> read_words(gpu::Context& ctx, const gpu::Buffer& buffer) {
  const std::vector<uint8_t> bytes = gpu::read_buffer_bytes(ctx, buffer);
  std::vector<uint32_t> words(bytes.size() / 4);
  std::memcpy(words.data(), bytes.data(), words.size() * 4);
  return words;
}

// A paged map's pages as read back: per page-table entry, its texels' words (empty
// when the entry is absent).
struct PagedMapContents {
  std::vector<std::vector<uint32_t>> pages;
};

PagedMapContents read_pages(gpu::Context& ctx, const gpu::Buffer& map, uint32_t virtual_resolution, uint32_t page_size,
                            uint32_t vec4s) {
  const std::vector<uint32_t> words = read_words(ctx, map);
  const uint32_t entries = shared::page_table_entries(virtual_resolution, page_size, 0);
  const size_t table_words = (size_t(entries) * 4 + 255) / 256 * 256 / 4;  // the table's bytes, as the atlas aligns them
  const size_t page_words = size_t(page_size) * page_size * vec4s * 4;
  PagedMapContents contents;
  contents.pages.resize(entries);
  for (uint32_t e = 0; e < entries; ++e) {
    if (words.at(e) == shared::kPageAbsent) continue;
    const size_t first = table_words + size_t(words[e] - 1) * page_words;
    contents.pages[e].assign(words.begin() + first, words.begin() + first + page_words);
  }
  return contents;
}

// The uv rectangle `box` covers on `view`'s map: its corners projected (in front of the light).
glm::vec4 uv_rectangle(const passes::LightView& view, const scene::Bounds& box) {
  glm::vec4 rect(1e9f, 1e9f, -1e9f, -1e9f);
  for (int c = 0; c < 8; ++c) {
    const glm::vec3 p(c & 1 ? box.max.x : box.min.x, c & 2 ? box.max.y : box.min.y, c & 4 ? box.max.z : box.min.z);
    const glm::vec4 clip = view.light_from_world * glm::vec4(p, 1.0f);
    const glm::vec2 uv = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
    rect = glm::vec4(glm::min(glm::vec2(rect), uv), glm::max(glm::vec2(rect.z, rect.w), uv));
  }
  return rect;
}

}  // namespace

// A 512^2 virtual map in pages of 32 with level 2 (128^2) all resident: every texel of
// every page is the 128^2 dense map's, for the sun and the spot (smoke, hair, meshes),
// with one vec4 of nodes a texel and with four (8 and 12 nodes lie between and share
// the same addressing).
TEST_F(PagedMapsTest, OneForcedLevelWithEveryPageResidentIsTheDenseMapBitForBit) {
  constexpr uint32_t kVirtual = 512, kPage = 32, kLevel = 2, kDense = kVirtual >> kLevel;
  for (const int nodes : {4, 16}) {
    SCOPED_TRACE("AVSM-" + std::to_string(nodes));
    const uint32_t kVec4s = uint32_t(nodes) / 4;  // a word per node, four to a vec4
    const scene::Scene dense_scene = default_scene(scene::ShadowLayout::dense, int(kDense), nodes);
    scene::Scene paged_scene = default_scene(scene::ShadowLayout::paged, int(kDense), nodes);
    for (scene::Light& light : paged_scene.lights) {
      light.shadow.virtual_resolution = int(kVirtual);
      light.shadow.page_size = int(kPage);
    }
    const passes::View view = passes::make_view(dense_scene.cameras.front(), kFrameWidth, kFrameHeight);
    renderer::SceneRenderer dense(ctx(), shaders(), dense_scene, kFrameWidth, kFrameHeight);
    renderer::SceneRenderer paged(ctx(), shaders(), paged_scene, kFrameWidth, kFrameHeight,
                                  {.unlimited_page_builds = true, .required_page_level = int(kLevel)});
    render_frames(ctx(), dense, view, 2);  // the second frame's capture has room for every segment
    render_frames(ctx(), paged, view, 3);  // pages whose capture overflowed are built again
    for (uint32_t light = 0; light < 2; ++light) {
      const std::string name = dense_scene.lights[light].name;
      ASSERT_FALSE(dense.shadows().frame_stats()[light].overflowed) << name;
      const passes::LightShadowStats& stats = paged.shadows().frame_stats()[light];
      ASSERT_TRUE(stats.pages) << name;
      ASSERT_FALSE(stats.overflowed) << name;
      const std::vector<uint32_t> dense_map = read_words(ctx(), dense.shadows().avsm_map(light));
      const std::vector<uint32_t> paged_map = read_words(ctx(), paged.shadows().avsm_map(light));
      ASSERT_EQ(dense_map.size(), size_t(kDense) * kDense * kVec4s * 4) << name;
      const uint32_t grid = kDense / kPage;
      const uint32_t first = shared::page_table_level_first(kVirtual, kPage, 0, kLevel);
      const uint32_t table_words = uint32_t((shared::page_table_entries(kVirtual, kPage, 0) * 4 + 255) / 256 * 256 / 4);
      size_t differing = 0, shadowed = 0;
      for (uint32_t py = 0; py < grid; ++py)
        for (uint32_t px = 0; px < grid; ++px) {
          const uint32_t word = paged_map.at(first + py * grid + px);
          ASSERT_NE(word, shared::kPageAbsent) << name << ": page (" << px << ", " << py << ") is not resident";
          const size_t slot_base = table_words + size_t(word - 1) * kPage * kPage * kVec4s * 4;
          for (uint32_t y = 0; y < kPage; ++y)
            for (uint32_t x = 0; x < kPage; ++x) {
              const size_t dense_texel = (size_t(py * kPage + y) * kDense + px * kPage + x) * kVec4s * 4;
              const size_t page_texel = slot_base + (size_t(y) * kPage + x) * kVec4s * 4;
              ASSERT_LT(page_texel + kVec4s * 4 - 1, paged_map.size()) << name;
              const bool same = std::memcmp(&dense_map[dense_texel], &paged_map[page_texel], kVec4s * 16) == 0;
              // The last node's transmittance (high 16 bits) below 1: something casts there.
              shadowed += (dense_map[dense_texel + kVec4s * 4 - 1] >> 16) < 0xffffu;
              if (!same && differing++ < 3) {
                std::ostringstream words;
                for (uint32_t w = 0; w < kVec4s * 4; ++w)
                  words << std::hex << " " << dense_map[dense_texel + w] << "/" << paged_map[page_texel + w];
                ADD_FAILURE() << name << ": texel (" << px * kPage + x << ", " << py * kPage + y
                              << ") differs; nodes dense/paged:" << words.str();
              }
            }
        }
      EXPECT_EQ(differing, 0u) << name;
      std::cout << "[ paged exact ] AVSM-" << nodes << " " << name << ": " << grid * grid << " pages of level " << kLevel
                << ", " << shadowed << " shadowed texels, " << differing << " differ from the dense " << kDense
                << "^2 map\n";
      EXPECT_GT(shadowed, 500u) << name << ": not vacuous";
    }
  }
}

// The default scene's lights paged so that every receiver reads the level of a dense
// kHeldLevel^2 map: a 512^2 virtual map in pages of 32, whose shadow.resolution of 128
// makes level 2 the fallback, and a page_lod_bias of 8 that sends every receiver there
// (the fallback level and those above: 21 pages). Slots of lists (the uncompressed
// technique, or the exact reference) hold 96 segments a texel, room for the hair
// curtain's at that level (the default 32 is not), in a pool of `pool_mib`.
constexpr uint32_t kHeldLevel = 128;
scene::Scene held_at_fallback_level(double pool_mib, const std::string& technique = "avsm") {
  scene::Scene scene = default_scene(scene::ShadowLayout::paged, int(kHeldLevel));
  for (scene::Light& light : scene.lights) {
    light.shadow.technique = technique;
    light.shadow.virtual_resolution = 512;
    light.shadow.page_size = 32;
    light.shadow.page_lod_bias = 8.0f;
    light.shadow.parameters["page_segments"] = 96;
    light.shadow.page_pool_mib = pool_mib;
  }
  return scene;
}

// The uncompressed reference paged: pages keep their capture lists in the light's pool
// (the looked-up list buffers), and lookups walk them. With every receiver held at the
// fallback level, each reads the same lists as the dense 128^2 reference does: the frames
// match but for the order in which each texel's segments multiply (a page's capture
// appends them in another order).
TEST_F(PagedMapsTest, PagedListsGiveTheDenseReferenceFrameAtTheirLevel) {
  scene::Scene dense_scene = default_scene(scene::ShadowLayout::dense, int(kHeldLevel));
  for (scene::Light& light : dense_scene.lights) light.shadow.technique = "uncompressed";
  scene::Scene paged_scene = held_at_fallback_level(48.0, "uncompressed");  // 1.5 MiB slots: 32 of them
  const passes::View view = passes::make_view(dense_scene.cameras.front(), kFrameWidth, kFrameHeight);
  renderer::SceneRenderer dense(ctx(), shaders(), dense_scene, kFrameWidth, kFrameHeight);
  renderer::SceneRenderer paged(ctx(), shaders(), paged_scene, kFrameWidth, kFrameHeight, {.unlimited_page_builds = true});
  render_frames(ctx(), dense, view, 2);  // the second frame's capture has room for every segment
  render_frames(ctx(), paged, view, 3);
  for (uint32_t light = 0; light < 2; ++light) {
    const std::string name = dense_scene.lights[light].name;
    ASSERT_FALSE(dense.shadows().frame_stats()[light].overflowed) << name;
    const passes::LightShadowStats& stats = paged.shadows().frame_stats()[light];
    ASSERT_TRUE(stats.pages) << name;
    EXPECT_FALSE(stats.overflowed) << name << ": a page's capture outgrew its slot";
    EXPECT_EQ(stats.pages->pending, 0u) << name;
    EXPECT_GT(stats.pages->requested, 4u) << name;
  }
  const gpu::ImageRGBA32F a = gpu::read_image(ctx(), dense.hdr(), renderer::SceneRenderer::kOutputLayout);
  const gpu::ImageRGBA32F b = gpu::read_image(ctx(), paged.hdr(), renderer::SceneRenderer::kOutputLayout);
  ASSERT_EQ(a.pixels.size(), b.pixels.size());
  double most = 0.0, sum = 0.0;
  for (size_t i = 0; i < a.pixels.size(); ++i) {
    const double d = std::abs(double(a.pixels[i]) - double(b.pixels[i]));
    most = std::max(most, d / std::max(1.0, double(std::abs(a.pixels[i]))));
    sum += d;
  }
  std::cout << "[ paged lists ] frame against the dense 128^2 reference: largest relative |d| " << most << ", mean |d| "
            << sum / double(a.pixels.size()) << "\n";
  // Two steps of the half floats the HDR image holds (the products' last bits differ).
  EXPECT_LT(most, 2.5e-3);
  EXPECT_LT(sum / double(a.pixels.size()), 1e-5);

  // Slots of 2 segments per texel: the pages that do not fit say so, frame after frame.
  for (scene::Light& light : paged_scene.lights) light.shadow.parameters["page_segments"] = 2;
  renderer::SceneRenderer cramped(ctx(), shaders(), paged_scene, kFrameWidth, kFrameHeight, {.unlimited_page_builds = true});
  render_frames(ctx(), cramped, view, 2);
  for (uint32_t light = 0; light < 2; ++light) {
    const passes::LightShadowStats& stats = cramped.shadows().frame_stats()[light];
    EXPECT_TRUE(stats.page_slot_full) << dense_scene.lights[light].name;
    EXPECT_TRUE(stats.lost_shadowing()) << dense_scene.lights[light].name;
    EXPECT_GT(stats.capture_requested, stats.capture_capacity) << dense_scene.lights[light].name;
  }
}

// A paged light's exact reference (ShadowOptions::keep_paged_reference, what
// avsm-capture --compare-to asks for): each page also keeps its capture lists, in a slot of
// a pool of lists with as many slots as the light's page pool. Held at the fallback level
// (as above), a paged AVSM light's quality figures (|T - T_exact| at each surface) are the
// dense AVSM 128^2 map's against its own reference.
TEST_F(PagedMapsTest, PagedLightsKeepAnExactReferenceForTheQualityFigures) {
  const scene::Scene dense_scene = default_scene(scene::ShadowLayout::dense, int(kHeldLevel));
  const scene::Scene paged_scene = held_at_fallback_level(1.0);  // 32 pages of AVSM-8, 48 MiB of lists
  const passes::View view = passes::make_view(dense_scene.cameras.front(), kFrameWidth, kFrameHeight);
  renderer::SceneRenderer dense(ctx(), shaders(), dense_scene, kFrameWidth, kFrameHeight, {.keep_reference = true});
  renderer::SceneRenderer paged(ctx(), shaders(), paged_scene, kFrameWidth, kFrameHeight,
                                {.keep_reference = true, .keep_paged_reference = true, .unlimited_page_builds = true});
  dense.enable_quality();
  paged.enable_quality();
  render_frames(ctx(), dense, view, 2);
  render_frames(ctx(), paged, view, 3);
  for (uint32_t light = 0; light < 2; ++light) {
    const passes::LightShadowStats& stats = paged.shadows().frame_stats()[light];
    EXPECT_FALSE(stats.page_slot_full) << dense_scene.lights[light].name;
    EXPECT_EQ(stats.pages->pending, 0u) << dense_scene.lights[light].name;
  }
  const std::vector<passes::PixelShadowError> a = dense.quality_results(), b = paged.quality_results();
  ASSERT_EQ(a.size(), b.size());
  double most = 0.0, total = 0.0;
  uint32_t surfaces = 0;
  for (size_t i = 0; i < a.size(); ++i) {
    ASSERT_EQ(a[i].surface < 0.0f, b[i].surface < 0.0f) << "pixel " << i;
    if (a[i].surface < 0.0f) continue;
    ++surfaces;
    total += a[i].surface;
    most = std::max(most, double(std::abs(a[i].surface - b[i].surface)));
  }
  std::cout << "[ paged ref   ] " << surfaces << " surface receivers, mean |T - T_exact| " << total / surfaces
            << " dense, largest difference from it paged " << most << "\n";
  EXPECT_GT(total / surfaces, 1e-5) << "not vacuous: AVSM-8 differs from the exact curve somewhere";
  EXPECT_LT(most, 1e-4);
}

// The camera's receivers ask for pages; after a few frames every page they asked for is
// resident (none pending), and the frame matches a dense 512^2 frame closely.
TEST_F(PagedMapsTest, ReceiversAskForThePagesTheyReadUntilTheMapConverges) {
  scene::Scene scene = default_scene(scene::ShadowLayout::paged, 256);
  for (scene::Light& light : scene.lights) light.shadow.virtual_resolution = 2048;
  const passes::View view = passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight);
  renderer::SceneRenderer paged(ctx(), shaders(), scene, kFrameWidth, kFrameHeight, {.unlimited_page_builds = true});
  render_frames(ctx(), paged, view, 1);
  const passes::PageStats first = *paged.shadows().frame_stats()[0].pages;
  EXPECT_EQ(first.built, 1u) << "the first frame builds the coarsest page";
  EXPECT_GT(first.pending, 0u) << "and its receivers ask for finer ones";
  render_frames(ctx(), paged, view, 3);
  for (uint32_t light = 0; light < 2; ++light) {
    const passes::PageStats& pages = *paged.shadows().frame_stats()[light].pages;
    EXPECT_EQ(pages.pending, 0u) << scene.lights[light].name;
    EXPECT_EQ(pages.unserved, 0u) << scene.lights[light].name;
    EXPECT_GE(pages.requested, 2u) << scene.lights[light].name;  // finer pages than the coarsest
    EXPECT_GE(pages.resident, pages.requested) << scene.lights[light].name;
    std::cout << "[ paged ask   ] " << scene.lights[light].name << ": " << pages.requested << " pages asked for, "
              << pages.resident << " resident of " << pages.slots << "\n";
  }
}

// The engine's resolution figure (passes/camera/quality/shadow_resolution_pass.h) follows
// the level the surfaces read (the lights' shadow.resolution of 64 lets receivers ask for
// every level: passes/shadows/shadow_settings.h, paged_fallback_level): a page_lod_bias
// of one level makes each receiver read the
// next coarser level (unless it already reads the coarsest), and its texel exactly twice as
// wide on screen (up to the change of the surface point's offset, which the level sets).
// With room in the pool (no bias) most lit receivers read texels at most 1.5 pixels wide.
TEST_F(PagedMapsTest, TheResolutionFigureFollowsTheLevelsTheSurfacesRead) {
  constexpr uint32_t kWidth = 2 * kFrameWidth, kHeight = 2 * kFrameHeight;  // fewer receivers at the coarsest level
  std::vector<passes::PixelShadowResolution> pixels[2];
  uint32_t coarsest[2] = {};  // per light
  for (const int bias : {0, 1}) {
    scene::Scene scene = default_scene(scene::ShadowLayout::paged, 64);
    for (scene::Light& light : scene.lights) light.shadow.page_lod_bias = float(bias);
    const passes::View view = passes::make_view(scene.cameras.front(), kWidth, kHeight);
    renderer::SceneRenderer paged(ctx(), shaders(), scene, kWidth, kHeight, {.unlimited_page_builds = true});
    paged.enable_resolution_figures();
    render_frames(ctx(), paged, view, 4);
    for (uint32_t light = 0; light < 2; ++light) {
      const passes::PageStats& pages = *paged.shadows().frame_stats()[light].pages;
      ASSERT_EQ(pages.pending, 0u) << scene.lights[light].name;
      ASSERT_EQ(pages.lod_bias, 0.0f) << scene.lights[light].name << ": the pool holds the requests";
    }
    for (uint32_t light = 0; light < 2; ++light) coarsest[light] = paged.shadows().frame_stats()[light].mip_levels - 1;
    pixels[bias] = paged.resolution_results();
  }
  ASSERT_EQ(pixels[0].size(), size_t(2) * kWidth * kHeight);
  uint32_t receivers = 0, matched = 0, others = 0;
  std::vector<float> level_steps, width_ratios;  // of the receivers that are not at the coarsest level
  for (size_t i = 0; i < pixels[0].size(); ++i) {
    const passes::PixelShadowResolution &fine = pixels[0][i], &biased = pixels[1][i];
    // The same receivers, but for a few at a map's edge, where the larger offset of the
    // surface point moves it out of the map.
    if (fine.level < 0.0f || biased.level < 0.0f) {
      others += fine.level >= 0.0f || biased.level >= 0.0f;
      continue;
    }
    ++receivers;
    matched += fine.texel_pixels <= 1.5f;
    if (biased.level >= float(coarsest[i / (kWidth * kHeight)])) continue;  // clamped
    level_steps.push_back(biased.level - fine.level);
    width_ratios.push_back(biased.texel_pixels / fine.texel_pixels);
  }
  std::sort(level_steps.begin(), level_steps.end());
  std::sort(width_ratios.begin(), width_ratios.end());
  const size_t n = level_steps.size();
  std::cout << "[ resolution  ] " << receivers << " lit receivers; with a bias of 1, " << n << " read a level "
            << level_steps[n / 2] << " coarser (5th to 95th percentile " << level_steps[n / 20] << " to "
            << level_steps[n - 1 - n / 20] << "), texels " << width_ratios[n / 2] << "x as wide; without it "
            << 100.0 * matched / receivers << "% at most 1.5 px\n";
  EXPECT_GT(receivers, 4000u);
  EXPECT_LT(others, receivers / 100);
  ASSERT_GT(n, receivers / 2);
  EXPECT_NEAR(level_steps[n / 2], 1.0f, 0.01f);
  EXPECT_NEAR(width_ratios[n / 2], 2.0f, 0.02f);
  EXPECT_GT(level_steps[n / 20], 0.9f);  // the surface point's offset moves with the level
  EXPECT_LT(level_steps[n - 1 - n / 20], 1.1f);
  EXPECT_GE(matched, receivers / 2);
}

// A directional light's map over a large scene (content/examples/cascades.scene.json, a
// 150 m avenue), seen through a long lens (3°: pixels of about 0.6 mm on the fence's
// shadow 5 m away). At 16384 texels its finest level is about a centimetre. At 262144
// the finest levels are clipmap windows around the camera (shared/pages.h), wider than
// the device's viewports, so their pages are captured with cropped projections
// (page_view()). The levels the receivers ask for lie outside their windows (which span
// about 1.6x a camera's distance at a usual field of view, but not at this one), so they
// read the finest level whose window holds them, never the coarsest: texels several
// times finer on screen, and the same frame away from the shadows' edges, without the
// self-shadowing that 16-bit node depths would give texels this fine
// (shadow_surface_point()).
TEST_F(PagedMapsTest, ADirectionalClipmapBeyondTheViewportsServesFinerTexelsNearTheCamera) {
  constexpr uint32_t kWidth = 480, kHeight = 270;
  struct Result {
    std::vector<passes::PixelShadowResolution> pixels;
    gpu::ImageRGBA32F hdr;
  };
  auto render = [&](int virtual_resolution) {
    scene::Scene scene = scene::load_scene(AVSM_EXAMPLES_DIR "/cascades.scene.json");
    scene::ShadowSettings& s = scene.lights.at(0).shadow;
    s.layout = scene::ShadowLayout::paged;
    s.fit = scene::ShadowFit::scene;
    s.cascades = 1;
    s.virtual_resolution = virtual_resolution;
    s.page_pool_mib = 48.0;
    scene::Camera& camera = scene.cameras.front();
    camera.target = {-1.0f, 0.0f, 0.5f};
    camera.vertical_fov = glm::radians(3.0f);
    renderer::SceneRenderer paged(ctx(), shaders(), scene, kWidth, kHeight, {.unlimited_page_builds = true});
    paged.enable_resolution_figures();
    render_frames(ctx(), paged, passes::make_view(camera, kWidth, kHeight), 5);
    const passes::PageStats& pages = *paged.shadows().frame_stats()[0].pages;
    EXPECT_EQ(pages.pending, 0u) << virtual_resolution;
    EXPECT_EQ(pages.lod_bias, 0.0f) << virtual_resolution << ": the pool holds the requests";
    return Result{paged.resolution_results(),
                  gpu::read_image(ctx(), paged.hdr(), renderer::SceneRenderer::kOutputLayout)};
  };
  const Result coarse = render(16384), fine = render(262144);
  // Levels of the 262144 map wider than the device's viewports: cropped page projections.
  uint32_t cropped_levels = 0;
  while ((262144u >> cropped_levels) > ctx().info().max_viewport_dimension) ++cropped_levels;
  ASSERT_GT(cropped_levels, 0u);
  std::vector<float> coarse_widths, fine_widths;
  uint32_t cropped = 0;
  float coarsest_read = 0.0f;
  for (size_t i = 0; i < fine.pixels.size(); ++i) {
    if (coarse.pixels[i].level < 0.0f || fine.pixels[i].level < 0.0f) continue;
    coarse_widths.push_back(coarse.pixels[i].texel_pixels);
    fine_widths.push_back(fine.pixels[i].texel_pixels);
    cropped += fine.pixels[i].level < float(cropped_levels);
    coarsest_read = std::max(coarsest_read, fine.pixels[i].level);
  }
  ASSERT_GT(fine_widths.size(), size_t(kWidth) * kHeight / 2);
  std::sort(coarse_widths.begin(), coarse_widths.end());
  std::sort(fine_widths.begin(), fine_widths.end());
  const float coarse_median = coarse_widths[coarse_widths.size() / 2], fine_median = fine_widths[fine_widths.size() / 2];
  // Away from edges (a 5x5 neighbourhood of one shade in the fine frame) the frames agree.
  auto shade = [](const gpu::ImageRGBA32F& image, uint32_t x, uint32_t y) {
    const float* p = image.at(x, y);
    return p[0] + p[1] + p[2];
  };
  uint32_t flat = 0, differing = 0;
  for (uint32_t y = 2; y + 2 < kHeight; ++y)
    for (uint32_t x = 2; x + 2 < kWidth; ++x) {
      float lo = 1e30f, hi = 0.0f;
      for (uint32_t v = y - 2; v <= y + 2; ++v)
        for (uint32_t u = x - 2; u <= x + 2; ++u) {
          lo = std::min(lo, shade(fine.hdr, u, v));
          hi = std::max(hi, shade(fine.hdr, u, v));
        }
      if (hi - lo > 0.02f * hi) continue;
      ++flat;
      differing += std::abs(shade(fine.hdr, x, y) - shade(coarse.hdr, x, y)) > 0.02f * hi;
    }
  std::cout << "[ clipmap     ] " << fine_widths.size() << " lit receivers, " << cropped << " reading levels 0.."
            << cropped_levels - 1 << " (cropped), none coarser than level " << coarsest_read << "; median texel "
            << coarse_median << " px at 16384, " << fine_median << " px at 262144; " << differing << " of " << flat
            << " pixels away from edges differ by over 2%\n";
  EXPECT_GT(cropped, fine_widths.size() / 2);
  EXPECT_LT(coarsest_read, 4.0f) << "the 16384 map's finest texels are level 4's";
  EXPECT_LT(fine_median, 0.5f * coarse_median);
  // Most of the frame is flat: streaks of self-shadowing on the lit ground would not be.
  EXPECT_GT(flat, fine_widths.size() * 7 / 10);
  // (What differs lies where the 16384 map's texels, 20 pixels wide, blur the edges.)
  EXPECT_LT(differing, flat / 50);
}

// Smoke and hair are receivers too: without the scene's meshes, the lighting cache's
// cells and the hair vertices still ask for pages (more than the coarsest), and the
// smoke's page_volume_lod_bias makes them ask for coarser, fewer ones (down to every level:
// shadow.resolution 64).
TEST_F(PagedMapsTest, SmokeAndHairAskForThePagesTheyRead) {
  uint32_t requested[2] = {};  // per volume bias 0, 2: both lights' pages
  for (const int bias : {0, 2}) {
    scene::Scene scene = default_scene(scene::ShadowLayout::paged, 64);
    for (scene::Light& light : scene.lights) light.shadow.page_volume_lod_bias = float(bias);
    scene.meshes.clear();  // no surface asks for pages
    const passes::View view = passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight);
    renderer::SceneRenderer paged(ctx(), shaders(), scene, kFrameWidth, kFrameHeight, {.unlimited_page_builds = true});
    render_frames(ctx(), paged, view, 4);
    for (uint32_t light = 0; light < 2; ++light) {
      const passes::PageStats& pages = *paged.shadows().frame_stats()[light].pages;
      EXPECT_EQ(pages.pending, 0u) << scene.lights[light].name;
      if (bias == 0) {
        EXPECT_GE(pages.requested, 2u) << scene.lights[light].name << ": finer pages than the coarsest";
      }
      requested[bias / 2] += pages.requested;
    }
  }
  std::cout << "[ paged ask   ] smoke and hair alone: " << requested[0] << " pages asked for, " << requested[1]
            << " with the smoke two levels coarser\n";
  EXPECT_LT(requested[1], requested[0]);
}

// Surface probes over the default scene's floor, facing up, every `step` metres.
void set_floor_probes(renderer::SceneRenderer& renderer, const scene::Bounds& bounds, float step) {
  std::vector<glm::vec3> points, normals;
  for (float x = bounds.min.x + step / 2; x < bounds.max.x; x += step)
    for (float z = bounds.min.z + step / 2; z < bounds.max.z; z += step) {
      points.push_back({x, bounds.min.y, z});
      normals.push_back({0.0f, 1.0f, 0.0f});
    }
  renderer.set_surface_probes(points, normals);
}

// A pool of six pages: receivers are served by the coarser levels that fit, the
// overflow is reported (unserved, pending), and the bias grows, but receivers never read
// coarser texels than the dense map of the lights' shadow.resolution (64^2: the pool
// must hold that level, four pages, and the root): no floor point that dense map
// shadows is left unshadowed.
TEST_F(PagedMapsTest, APoolOfAFewPagesServesCoarserLevelsAndReportsTheOverflow) {
  constexpr int kDense = 64;
  scene::Scene scene = default_scene(scene::ShadowLayout::paged, kDense);
  for (scene::Light& light : scene.lights) {
    light.shadow.virtual_resolution = 2048;
    light.shadow.page_size = 32;
    light.shadow.page_pool_mib = 6.0 * 32 * 32 * 32 / double(1 << 20);  // six AVSM-8 pages of 32^2
  }
  const passes::View view = passes::make_view(scene.cameras.front(), kFrameWidth, kFrameHeight);
  renderer::SceneRenderer paged(ctx(), shaders(), scene, kFrameWidth, kFrameHeight, {.unlimited_page_builds = true});
  set_floor_probes(paged, scene.bounds, 0.1f);
  // Frame 1 builds the coarsest page; frame 2 builds what fits of what frame 1 asked for.
  render_frames(ctx(), paged, view, 2);
  const passes::LightShadowStats overflowed = paged.shadows().frame_stats()[0];
  EXPECT_EQ(overflowed.pages->slots, 6u);
  EXPECT_EQ(overflowed.pages->resident, 6u);
  EXPECT_GT(overflowed.pages->unserved, 0u);
  EXPECT_GT(overflowed.pages->pending, 0u);
  EXPECT_TRUE(overflowed.lost_shadowing());
  EXPECT_GT(overflowed.pages->lod_bias, 0.0f);
  const std::vector<std::vector<float>> served = paged.probe_results();

  renderer::SceneRenderer dense(ctx(), shaders(), default_scene(scene::ShadowLayout::dense, kDense), kFrameWidth,
                                kFrameHeight);
  set_floor_probes(dense, scene.bounds, 0.1f);
  render_frames(ctx(), dense, view, 1);
  const std::vector<std::vector<float>> reference = dense.probe_results();
  for (uint32_t light = 0; light < 2; ++light) {
    uint32_t shadowed = 0, unshadowed = 0;
    for (size_t i = 0; i < reference[light].size(); ++i) {
      if (reference[light][i] >= 0.5f) continue;
      ++shadowed;
      unshadowed += served[light][i] > 0.9f;
    }
    std::cout << "[ overflow    ] " << scene.lights[light].name << ": " << shadowed
              << " floor points the dense 64^2 map shadows (T < 0.5); " << unshadowed
              << " of them unshadowed (T > 0.9) from the coarser pages\n";
    EXPECT_GT(shadowed, 20u) << scene.lights[light].name;
    EXPECT_EQ(unshadowed, 0u) << scene.lights[light].name;
  }
  // The bias grows until the requests fit (at the dense map's level at the most).
  render_frames(ctx(), paged, view, 3);
  const passes::LightShadowStats& settled = paged.shadows().frame_stats()[0];
  EXPECT_GE(settled.pages->lod_bias, overflowed.pages->lod_bias);
  EXPECT_LE(settled.pages->lod_bias, 5.0f);
  EXPECT_EQ(settled.pages->unserved, 0u);
  EXPECT_EQ(settled.pages->pending, 0u);
}

// The default scene's box moves by 30 cm. With a level forced resident (a camera that
// sees only sky asks for nothing else, so requests do not change): the next frame
// builds exactly the resident pages that the box's old or new bounds overlap (widened
// by a texel of their level), every other page keeps its texels bit for bit, and the
// whole map then equals a map built from nothing for the moved scene.
TEST_F(PagedMapsTest, AMovedBoxRebuildsExactlyThePagesItsOldAndNewBoundsOverlap) {
  constexpr uint32_t kVirtual = 1024, kPage = 32, kLevel = 2, kVec4s = 2;  // AVSM-8
  scene::Scene scene = default_scene(scene::ShadowLayout::paged, 256);
  for (scene::Light& light : scene.lights) {
    light.shadow.virtual_resolution = int(kVirtual);
    light.shadow.page_size = int(kPage);
  }
  scene::Camera sky = scene.cameras.front();
  sky.position = {0.0f, 1.0f, 30.0f};
  sky.target = {0.0f, 1.5f, 60.0f};
  const passes::View view = passes::make_view(sky, kFrameWidth, kFrameHeight);
  const passes::ShadowOptions options{.unlimited_page_builds = true, .required_page_level = int(kLevel)};
  renderer::SceneRenderer paged(ctx(), shaders(), scene, kFrameWidth, kFrameHeight, options);
  render_frames(ctx(), paged, view, 3);  // pages whose capture overflowed are built again

  const auto box = std::find_if(scene.meshes.begin(), scene.meshes.end(), [](const scene::Mesh& m) { return m.name == "stage/box"; });
  ASSERT_NE(box, scene.meshes.end());
  const uint32_t box_index = uint32_t(box - scene.meshes.begin());
  const scene::Bounds old_bounds = box->bounds;
  std::vector<PagedMapContents> before;
  for (uint32_t light = 0; light < 2; ++light) {
    ASSERT_EQ(paged.shadows().frame_stats()[light].pages->pending, 0u);
    before.push_back(read_pages(ctx(), paged.shadows().avsm_map(light), kVirtual, kPage, kVec4s));
  }
  scene::Mesh& moved = *box;
  for (glm::vec3& p : moved.positions) p.x -= 0.3f;
  moved.bounds = {old_bounds.min - glm::vec3(0.3f, 0, 0), old_bounds.max - glm::vec3(0.3f, 0, 0)};
  paged.update_mesh(box_index, moved);
  render_frames(ctx(), paged, view, 1);

  renderer::SceneRenderer fresh(ctx(), shaders(), scene, kFrameWidth, kFrameHeight, options);
  render_frames(ctx(), fresh, view, 3);
  const passes::PageTable expected_layout(kVirtual, kPage, 1);
  for (uint32_t light = 0; light < 2; ++light) {
    const std::string name = scene.lights[light].name;
    const passes::LightView virtual_view = paged.shadows().map_views(light).front();
    const PagedMapContents after = read_pages(ctx(), paged.shadows().avsm_map(light), kVirtual, kPage, kVec4s);
    const PagedMapContents rebuilt = read_pages(ctx(), fresh.shadows().avsm_map(light), kVirtual, kPage, kVec4s);
    const glm::vec4 old_rect = uv_rectangle(virtual_view, old_bounds), new_rect = uv_rectangle(virtual_view, moved.bounds);
    uint32_t overlapped = 0, kept = 0, changed = 0, resident = 0;
    for (uint32_t e = 0; e < expected_layout.entries(); ++e) {
      if (before[light].pages[e].empty()) continue;
      ++resident;
      const passes::PageKey key = expected_layout.key(e);
      const float raster = float(std::max(kVirtual >> key.level, kPage)), texel = 1.0f / raster;
      const glm::vec2 first = glm::vec2(key.page * kPage) / raster - texel, end = glm::vec2((key.page + 1u) * kPage) / raster + texel;
      auto overlaps = [&](const glm::vec4& r) { return r.x <= end.x && first.x <= r.z && r.y <= end.y && first.y <= r.w; };
      const bool hit = overlaps(old_rect) || overlaps(new_rect);
      overlapped += hit;
      ASSERT_FALSE(after.pages[e].empty()) << name << ": page " << e << " left the pool";
      if (!hit) {
        kept += after.pages[e] == before[light].pages[e];
        EXPECT_EQ(after.pages[e], before[light].pages[e]) << name << ": page " << e << " (level " << key.level
                                                          << ") changed although the box is nowhere near it";
      }
      changed += after.pages[e] != before[light].pages[e];
      ASSERT_FALSE(rebuilt.pages[e].empty()) << name << ": page " << e;
      EXPECT_EQ(after.pages[e], rebuilt.pages[e]) << name << ": page " << e << " (level " << key.level
                                                  << ") differs from the moved scene's map built from nothing";
    }
    const passes::PageStats& pages = *paged.shadows().frame_stats()[light].pages;
    std::cout << "[ paged move  ] " << name << ": " << resident << " pages resident, " << overlapped
              << " overlapped by the box's old or new bounds, " << pages.invalidated << " invalidated, " << pages.built
              << " built, " << changed << " changed, " << kept << " kept bit for bit\n";
    EXPECT_EQ(pages.invalidated, overlapped) << name;
    EXPECT_EQ(pages.built, overlapped) << name;
    EXPECT_GT(changed, 0u) << name << ": the box's shadow moved on some page";
    EXPECT_LT(overlapped * 3, resident) << name << ": a small box touches few pages";
  }
}

}  // namespace paged_maps_test
}  // namespace avsm
