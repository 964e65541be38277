// Every kind of light and map ShadowMaps builds, against transmittance integrated on the
// CPU through constant-density boxes: point lights (a cube of six faces, and a ring of
// receivers across a face seam), sixteen mixed lights in one scene, the map budget,
// directional maps fitted to the camera (stable under sub-texel camera motion),
// cascades and clustered maps (seed 004).
#include <gtest/gtest.h>

#include <glm/gtc/matrix_transform.hpp>
#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <cmath>
#include <iostream>
#include <map>
#include <string>
#include <vector>

#include "gpu/device_limits.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_maps.h"
#include "passes/frame/view.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"
#include "shared/pages.h"
#include "support/gpu_test.h"
#include "support/test_volumes.h"

namespace avsm {
namespace light_maps_test {  // one per file: test targets are unity builds
namespace {

using LightMapsTest = testing::GpuTest;

constexpr uint32_t kFrameWidth = 64, kFrameHeight = 36;

// A box of density 1 over voxels [0, n)^3 of size kVoxel, offset to `origin`: its
// trilinear density is 1 inside the voxel centres and ramps to 0 over one voxel.
constexpr float kVoxel = 0.1f;
constexpr float kSigma = 0.5f;  // extinction per unit density per world unit

struct Box {
  glm::vec3 origin{0.0f};  // world position of voxel (0, 0, 0)'s centre
  int voxels = 16;
  glm::vec3 low() const { return origin; }
  glm::vec3 high() const { return origin + glm::vec3(float(voxels - 1) * kVoxel); }
  glm::vec3 centre() const { return 0.5f * (low() + high()); }
  // The trilinear density at p: per axis 1 between the voxel centres, 0 a voxel beyond.
  float density(const glm::vec3& p) const {
    float d = 1.0f;
    for (int a = 0; a < 3; ++a) {
      const float inside = std::min(p[a] - (low()[a] - kVoxel), (high()[a] + kVoxel) - p[a]) / kVoxel;
      d *= std::clamp(inside, 0.0f, 1.0f);
    }
    return d;
  }
};

// exp(-sigma * integral of the boxes' density along the segment from `from` to `to`).
float reference_transmittance(const std::vector<Box>& boxes, const glm::vec3& from, const glm::vec3& to) {
  constexpr int kSteps = 4000;
  const float length = glm::length(to - from);
  double optical = 0.0;
  for (int i = 0; i < kSteps; ++i) {
    const glm::vec3 p = from + (to - from) * ((float(i) + 0.5f) / float(kSteps));
    for (const Box& box : boxes) optical += double(box.density(p)) * double(length) / kSteps;
  }
  return float(std::exp(-double(kSigma) * optical));
}

scene::Scene box_scene(const std::vector<Box>& boxes) {
  scene::Scene scene;
  scene.file = "light maps test scene (built in the test)";
  for (size_t i = 0; i < boxes.size(); ++i) {
    scene::VolumeOptions options;
    options.extinction_scale = kSigma;
    options.transform = glm::translate(glm::mat4(1.0f), boxes[i].origin);
    const int n = boxes[i].voxels - 1;
    scene.volumes.push_back(testing::load_box_volume({{glm::ivec3(0), glm::ivec3(n), 1.0f}}, kVoxel, options));
    scene.volumes.back().name = "box " + std::to_string(i);
    scene.bounds.extend(scene.volumes.back().world_bounds);
  }
  scene::Camera camera;
  camera.position = scene.bounds.center() + glm::vec3(0.0f, 2.0f, 12.0f);
  camera.target = scene.bounds.center();
  scene.cameras.push_back(camera);
  return scene;
}

scene::Light make_light(const std::string& name, scene::LightType type, int resolution,
                        const std::string& technique = "avsm") {
  scene::Light light;
  light.name = name;
  light.type = type;
  light.shadow.technique = technique;
  light.shadow.nodes = 8;
  light.shadow.resolution = resolution;
  return light;
}

// Renders frames and returns the last one's probes, [light][point].
std::vector<std::vector<float>> render_probes(gpu::Context& ctx, renderer::SceneRenderer& renderer,
                                              const scene::Camera& camera, int frames = 2) {
  rg::vulkan::Executor executor(ctx, gpu::TimestampMode::Exact);
  for (int frame = 0; frame < frames; ++frame) {
    rg::Graph graph = renderer.build_frame(passes::make_view(camera, kFrameWidth, kFrameHeight));
    ctx.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
    renderer.finish_frame();
  }
  return renderer.probe_results();
}

// Where a light shines from at p: its position, or far back along its direction.
glm::vec3 light_origin(const scene::Light& light, const glm::vec3& p) {
  return light.type == scene::LightType::directional ? p - glm::normalize(light.direction) * 100.0f : light.position;
}

struct ProbeError {
  float mean = 0.0f, max = 0.0f;
  int shadowed = 0;  // probes whose reference is below 0.95
};

ProbeError probe_error(const std::vector<Box>& boxes, const scene::Light& light, const std::vector<glm::vec3>& points,
                       const std::vector<float>& got) {
  ProbeError e;
  for (size_t i = 0; i < points.size(); ++i) {
    const float want = reference_transmittance(boxes, light_origin(light, points[i]), points[i]);
    const float error = std::abs(got.at(i) - want);
    e.mean += error / float(points.size());
    e.max = std::max(e.max, error);
    e.shadowed += want < 0.95f;
  }
  return e;
}

// ---- Point lights ----

// A point light among six boxes, one on each side: every face of its cube shadows what
// lies behind its box, built from lists and in fixed memory.
TEST_F(LightMapsTest, PointLightShadowsEveryFaceOfItsCube) {
  const glm::vec3 light_position(0.0f);
  std::vector<Box> boxes;
  const glm::vec3 axes[6] = {{1, 0, 0}, {-1, 0, 0}, {0, 1, 0}, {0, -1, 0}, {0, 0, 1}, {0, 0, -1}};
  for (const glm::vec3& axis : axes) {
    Box box;
    box.origin = axis * 1.5f - glm::vec3(0.75f);  // 1.5 m from the light, 1.5 m wide
    boxes.push_back(box);
  }
  for (scene::ShadowBuild build : {scene::ShadowBuild::lists, scene::ShadowBuild::fixed}) {
    scene::Scene scene = box_scene(boxes);
    scene::Light point = make_light("point", scene::LightType::point, 64);
    point.position = light_position;
    point.shadow.build = build;
    scene.lights.push_back(point);
    std::vector<glm::vec3> probes;
    for (const glm::vec3& axis : axes)  // behind each box, and off-axis through its side
      for (const glm::vec3& offset : {glm::vec3(0.0f), glm::vec3(0.2f, 0.3f, -0.25f)}) probes.push_back(axis * 3.0f + offset);
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
    renderer.set_probes(probes);
    const std::vector<std::vector<float>> results = render_probes(ctx(), renderer, scene.cameras.front());
    const passes::LightShadowStats& stats = renderer.shadows().frame_stats().at(0);
    EXPECT_EQ(stats.maps, 6u);
    EXPECT_EQ(stats.map_kind, "cube");
    EXPECT_FALSE(stats.lost_shadowing());
    const ProbeError e = probe_error(boxes, point, probes, results.at(0));
    std::cout << "[ point cube  ] " << scene::to_string(build) << ": mean error " << e.mean << ", max " << e.max
              << " over " << probes.size() << " probes (" << e.shadowed << " shadowed)\n";
    EXPECT_EQ(e.shadowed, int(probes.size()));  // not vacuous: every probe lies behind a box
    EXPECT_LT(e.max, 0.03f) << scene::to_string(build);
  }
}

// A ring of receivers around the light crossing the +x/+z face seam behind one box that
// straddles it: the transmittance follows the integrated one on both faces and across
// the seam, with no crack (a jump to 1, or a step) where the lookup changes faces.
// Returns the largest step error at the seam.
float expect_no_crack_at_a_face_seam(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, scene::ShadowLayout layout) {
  Box box;
  box.voxels = 24;
  const float half = 0.5f * float(box.voxels - 1) * kVoxel;
  const glm::vec3 seam_direction = glm::normalize(glm::vec3(1.0f, 0.0f, 1.0f));
  box.origin = seam_direction * 2.0f - glm::vec3(half);  // centred on the seam, 2 m out
  scene::Scene scene = box_scene({box});
  scene::Light point = make_light("point", scene::LightType::point, 64);
  point.position = glm::vec3(0.0f);
  point.shadow.filter = scene::ShadowFilter::bilinear;
  passes::ShadowOptions options;
  if (layout == scene::ShadowLayout::paged) {
    // Faces of 16384^2 in pages of 32, level 7 (128^2: a face keeps the guard texels of
    // its coarsest level, one page, so it spans about as many texels as the dense 64^2
    // one) resident throughout.
    point.shadow.layout = layout;
    point.shadow.virtual_resolution = 16384;
    point.shadow.page_size = 32;
    options.required_page_level = 7;
    options.unlimited_page_builds = true;
  }
  scene.lights.push_back(point);
  // 121 receivers 4 m out, from 25 to 65 degrees around y (the seam is at 45), two heights.
  std::vector<glm::vec3> ring;
  for (float y : {0.0f, 0.35f})
    for (int i = 0; i <= 60; ++i) {
      const float angle = glm::radians(25.0f + 40.0f * float(i) / 60.0f);
      ring.emplace_back(4.0f * std::cos(angle), y, 4.0f * std::sin(angle));
    }
  renderer::SceneRenderer renderer(ctx, shaders, scene, kFrameWidth, kFrameHeight, options);
  // Looked up as surfaces facing the light, as the opaque pass looks up walls.
  std::vector<glm::vec3> facing_the_light;
  for (const glm::vec3& p : ring) facing_the_light.push_back(glm::normalize(point.position - p));
  renderer.set_surface_probes(ring, facing_the_light);
  const std::vector<float> got = render_probes(ctx, renderer, scene.cameras.front(), 3).at(0);
  float max_error = 0.0f, max_step_at_seam = 0.0f, max_step_elsewhere = 0.0f;
  int shadowed = 0;
  for (size_t i = 0; i < ring.size(); ++i) {
    const float want = reference_transmittance({box}, point.position, ring[i]);
    max_error = std::max(max_error, std::abs(got[i] - want));
    shadowed += want < 0.9f;
    if (i % 61 == 0) continue;
    // The step between neighbours against the reference's own step there.
    const float step = std::abs((got[i] - got[i - 1]) -
                                (want - reference_transmittance({box}, point.position, ring[i - 1])));
    const bool at_seam = std::abs(int(i % 61) - 30) <= 2;
    (at_seam ? max_step_at_seam : max_step_elsewhere) = std::max(at_seam ? max_step_at_seam : max_step_elsewhere, step);
  }
  std::cout << "[ cube seam   ] " << scene::to_string(layout) << ": max error " << max_error
            << ", step error at the seam " << max_step_at_seam << ", elsewhere " << max_step_elsewhere << " ("
            << shadowed << " of " << ring.size() << " shadowed)\n";
  EXPECT_GT(shadowed, int(ring.size()) / 2);  // the box covers the seam: the test sees it
  EXPECT_LT(max_error, 0.03f);
  EXPECT_LT(max_step_at_seam, 0.02f);
  return max_step_at_seam;
}

TEST_F(LightMapsTest, PointLightLookupsDoNotCrackAtAFaceSeam) {
  expect_no_crack_at_a_face_seam(ctx(), shaders(), scene::ShadowLayout::dense);
}

// The same with paged faces: no crack where the lookup changes faces, at a level whose
// texels are as wide as the dense map's.
TEST_F(LightMapsTest, PagedPointLightLookupsDoNotCrackAtAFaceSeam) {
  expect_no_crack_at_a_face_seam(ctx(), shaders(), scene::ShadowLayout::paged);
}

// ---- Paged maps: page and level seams ----

// A line of floor receivers along the shadow that a sun low in the sky casts from one
// smoke box, seen by a camera looking along it, so that the lookups cross page
// boundaries and, as the distance grows, levels. Returns per receiver the surface
// lookup's transmittance after the map converged (the receivers ask for their own
// pages: shaders/passes/shadows/inspection/shadow_probe.comp).
struct SeamLine {
  std::vector<Box> boxes;
  scene::Light sun;
  scene::Camera camera;
  std::vector<glm::vec3> points;
  static constexpr uint32_t kWidth = 320, kHeight = 180;
};

SeamLine seam_line() {
  SeamLine line;
  Box box;
  box.voxels = 24;
  box.origin = glm::vec3(-1.15f, 1.0f, -1.15f);
  line.boxes = {box};
  line.sun = make_light("sun", scene::LightType::directional, 64);
  line.sun.direction = glm::normalize(glm::vec3(0.0f, -std::sin(glm::radians(35.0f)), -std::cos(glm::radians(35.0f))));
  line.sun.shadow.fit = scene::ShadowFit::scene;
  line.sun.shadow.filter = scene::ShadowFilter::bilinear;
  line.camera.position = glm::vec3(0.6f, 1.6f, 3.5f);
  line.camera.target = glm::vec3(0.3f, 0.0f, -3.0f);
  for (float z = 0.5f; z >= -6.5f; z -= 0.02f) line.points.emplace_back(0.3f, 0.0f, z);
  return line;
}

struct SeamLookups {
  std::vector<float> transmittance;
  passes::LightView map;  // the sun's (virtual, when paged) map
  passes::PageStats pages;
};

SeamLookups look_up_seam_line(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const SeamLine& line,
                              scene::Light sun) {
  scene::Scene scene = box_scene(line.boxes);
  scene.cameras = {line.camera};
  scene.lights = {sun};
  renderer::SceneRenderer renderer(ctx, shaders, scene, SeamLine::kWidth, SeamLine::kHeight,
                                   {.unlimited_page_builds = true});
  renderer.set_surface_probes(line.points, std::vector<glm::vec3>(line.points.size(), glm::vec3(0.0f, 1.0f, 0.0f)));
  rg::vulkan::Executor executor(ctx, gpu::TimestampMode::Exact);
  // Frame 1 builds the root; the receivers' requests are built by the frames after it.
  for (int frame = 0; frame < 4; ++frame) {
    rg::Graph graph = renderer.build_frame(passes::make_view(line.camera, SeamLine::kWidth, SeamLine::kHeight));
    ctx.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
    renderer.finish_frame();
  }
  const passes::LightShadowStats& stats = renderer.shadows().frame_stats().at(0);
  EXPECT_FALSE(stats.lost_shadowing()) << scene::to_string(sun.shadow.layout);
  return {renderer.probe_results().at(0), renderer.shadows().map_views(0).at(0),
          stats.pages ? *stats.pages : passes::PageStats{}};
}

// Per neighbouring receivers (i - 1, i): how much the lookup's step differs from the
// integrated transmittance's.
std::vector<float> step_errors(const SeamLine& line, const std::vector<float>& got) {
  std::vector<float> errors(line.points.size(), 0.0f);
  const auto want = [&](size_t i) {
    return reference_transmittance(line.boxes, light_origin(line.sun, line.points[i]), line.points[i]);
  };
  float previous = want(0);
  for (size_t i = 1; i < line.points.size(); ++i) {
    const float current = want(i);
    errors[i] = std::abs((got.at(i) - got.at(i - 1)) - (current - previous));
    previous = current;
  }
  return errors;
}

// Receivers straddling a page boundary or a level boundary of a paged map (all its pages
// built, 8192^2 in pages of 32) step no more, against the integrated transmittance, than
// the dense map of the coarser level they read does between any neighbours on the line.
TEST_F(LightMapsTest, PagedLookupsStepNoMoreAtPageAndLevelBoundariesThanTheDenseMap) {
  constexpr uint32_t kVirtual = 8192, kPage = 32;
  const SeamLine line = seam_line();
  scene::Light paged_sun = line.sun;
  paged_sun.shadow.layout = scene::ShadowLayout::paged;
  paged_sun.shadow.virtual_resolution = int(kVirtual);
  paged_sun.shadow.page_size = int(kPage);
  paged_sun.shadow.resolution = int(kPage);  // receivers may read every level down to the root
  const SeamLookups paged = look_up_seam_line(ctx(), shaders(), line, paged_sun);
  EXPECT_EQ(paged.pages.pending, 0u);
  EXPECT_EQ(paged.pages.unserved, 0u);

  // The level each receiver reads, as shadow_paged_lod() picks it (no bias: the pool holds
  // every request), and the page of that level and the next that holds it.
  const passes::View view = passes::make_view(line.camera, SeamLine::kWidth, SeamLine::kHeight);
  const float radians_per_pixel = 2.0f / (std::abs(view.projection[1][1]) * float(view.height));
  const uint32_t levels = shared::page_level_count(kVirtual, kPage);
  std::vector<float> lod(line.points.size());
  std::vector<glm::vec2> uv(line.points.size());
  for (size_t i = 0; i < line.points.size(); ++i) {
    const glm::vec3& p = line.points[i];
    const float pixel = glm::distance(p, view.camera_position) * radians_per_pixel;
    lod[i] = std::clamp(std::log2(pixel / paged.map.texel_size(0.0f)), 0.0f, float(levels - 1));
    const glm::vec4 clip = paged.map.light_from_world * glm::vec4(p, 1.0f);
    uv[i] = glm::vec2(clip) / clip.w * 0.5f + 0.5f;
  }
  const auto page_of = [&](size_t i, uint32_t level) {
    return glm::uvec2(glm::floor(uv[i] * float((kVirtual >> level) / kPage)));
  };
  const std::vector<float> paged_steps = step_errors(line, paged.transmittance);
  // Per level (the coarser of the two a pair reads): the largest step at a page or
  // level boundary, and elsewhere.
  std::map<uint32_t, float> at_boundary, elsewhere;
  uint32_t page_boundaries = 0, level_boundaries = 0;
  for (size_t i = 1; i < line.points.size(); ++i) {
    const uint32_t level = uint32_t(std::floor(lod[i])), coarser = std::min(level + 1, levels - 1);
    const bool level_boundary = uint32_t(std::floor(lod[i - 1])) != level;
    const bool page_boundary = page_of(i, level) != page_of(i - 1, level) || page_of(i, coarser) != page_of(i - 1, coarser);
    page_boundaries += page_boundary;
    level_boundaries += level_boundary;
    float& largest = (page_boundary || level_boundary ? at_boundary : elsewhere)[coarser];
    largest = std::max(largest, paged_steps[i]);
  }
  EXPECT_GE(page_boundaries, 4u) << "the line crosses pages";
  EXPECT_GE(level_boundaries, 1u) << "the line crosses levels";
  int shadowed = 0;
  for (size_t i = 0; i < line.points.size(); ++i)
    shadowed += reference_transmittance(line.boxes, light_origin(line.sun, line.points[i]), line.points[i]) < 0.9f;
  EXPECT_GT(shadowed, int(line.points.size()) / 3) << "the line lies in the box's shadow";

  for (const auto& [level, paged_step] : at_boundary) {
    scene::Light dense_sun = line.sun;
    dense_sun.shadow.resolution = int(kVirtual >> level);
    const std::vector<float> dense_steps = step_errors(line, look_up_seam_line(ctx(), shaders(), line, dense_sun).transmittance);
    const float dense_step = *std::max_element(dense_steps.begin(), dense_steps.end());
    std::cout << "[ page seams  ] reading level " << level << " (" << (kVirtual >> level)
              << "^2): step error at page and level boundaries " << paged_step << ", elsewhere "
              << elsewhere[level] << "; the dense " << (kVirtual >> level) << "^2 map's largest " << dense_step << "\n";
    EXPECT_LE(paged_step, dense_step + 1e-3f) << "level " << level;
  }
  std::cout << "[ page seams  ] " << line.points.size() << " receivers, " << shadowed << " shadowed; "
            << page_boundaries << " pairs straddle a page, " << level_boundaries << " a level; " << paged.pages.resident
            << " pages resident\n";
}

// ---- Many lights ----

// One technique per light of the sixteen below, with the tolerance its box test has
// (tests/passes/avsm_shadow_test.cpp, "...MatchBeerLambertThroughABox").
struct TechniqueCase {
  const char* name;
  float tolerance;
  std::map<std::string, double> parameters;
  bool builds_fixed;
};
const TechniqueCase kTechniqueCases[] = {
    {"avsm", 0.03f, {}, true},
    {"uncompressed", 0.03f, {}, false},
    {"dsm", 0.03f, {{"error", 0.01}}, false},
    {"osm", 0.11f, {{"slices", 32}}, true},
    {"fom", 0.2f, {{"terms", 16}}, true},
};

// Sixteen shadowed lights of all three kinds and every technique around one box, the
// last six built in fixed memory where the technique can: each light shadows the point
// behind the box from it.
TEST_F(LightMapsTest, SixteenMixedLightsAllCast) {
  Box box;
  box.origin = glm::vec3(-0.75f);
  const std::vector<Box> boxes = {box};
  scene::Scene scene = box_scene(boxes);
  std::vector<glm::vec3> probes;
  for (int i = 0; i < 16; ++i) {
    const float angle = glm::two_pi<float>() * float(i) / 16.0f;
    const glm::vec3 around(std::cos(angle), 0.3f * float(i % 3) - 0.3f, std::sin(angle));
    const scene::LightType type = i % 3 == 0 ? scene::LightType::directional
                                 : i % 3 == 1 ? scene::LightType::spot
                                              : scene::LightType::point;
    const TechniqueCase& technique = kTechniqueCases[i % 5];
    scene::Light light = make_light("light " + std::to_string(i), type, 32, technique.name);
    light.shadow.parameters = technique.parameters;
    light.position = box.centre() + around * 4.0f;
    light.direction = glm::normalize(box.centre() - light.position);
    light.outer_cone_angle = glm::radians(30.0f);
    light.inner_cone_angle = glm::radians(20.0f);
    if (i >= 10 && technique.builds_fixed) light.shadow.build = scene::ShadowBuild::fixed;
    scene.lights.push_back(light);
    probes.push_back(box.centre() - around * 1.6f);  // behind the box from light i
  }
  renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
  renderer.set_probes(probes);
  const std::vector<std::vector<float>> results = render_probes(ctx(), renderer, scene.cameras.front());
  ASSERT_EQ(results.size(), 16u);
  for (uint32_t i = 0; i < 16; ++i) {
    const scene::Light& light = scene.lights[i];
    const float want = reference_transmittance(boxes, light_origin(light, probes[i]), probes[i]);
    EXPECT_LT(want, 0.6f) << light.name;
    EXPECT_NEAR(results[i][i], want, kTechniqueCases[i % 5].tolerance)
        << light.name << " (" << scene::to_string(light.type) << ", " << light.shadow.technique << ", "
        << scene::to_string(light.shadow.build) << ")";
    EXPECT_FALSE(renderer.shadows().frame_stats()[i].lost_shadowing()) << light.name;
  }
  std::cout << "[ 16 lights   ] atlas " << renderer.shadows().atlas_bytes() << " bytes\n";
}

// ---- The map budget ----

TEST_F(LightMapsTest, MapsOverTheBudgetAreAnErrorNamingTheLightsOrAreLowered) {
  Box box;
  scene::Scene scene = box_scene({box});
  for (int i = 0; i < 3; ++i) scene.lights.push_back(make_light("sun" + std::to_string(i), scene::LightType::directional, 512));
  passes::ShadowMaps maps(ctx(), shaders());
  passes::ShadowOptions options;
  options.map_budget_bytes = 4ull << 20;  // three AVSM-8 512^2 maps take 8 MiB each
  try {
    maps.set_scene(scene, options);
    FAIL() << "no error for maps over the budget";
  } catch (const passes::ShadowBudgetError& e) {
    const std::string message = e.what();
    EXPECT_NE(message.find(scene.file.string()), std::string::npos) << message;
    EXPECT_NE(message.find("light 1 'sun1' 8.00 MiB"), std::string::npos) << message;
    EXPECT_NE(message.find("over the budget of 4.00 MiB"), std::string::npos) << message;
    EXPECT_NE(message.find("budget_mib"), std::string::npos) << message;
  }
  options.fit_budget = true;
  maps.set_scene(scene, options);
  EXPECT_LE(maps.atlas_bytes(), options.map_budget_bytes);
  uint32_t lowered = 0;
  for (uint32_t i = 0; i < 3; ++i) lowered += maps.map_layout(i).resolution < 512;
  EXPECT_GE(lowered, 2u);  // 3 x 512^2 -> fits only with most lowered to 256^2
}

// Over the budget with many lights, the message stays a line: the largest few lights by
// name, largest first, and how many more there are with their bytes.
TEST_F(LightMapsTest, MapsOverTheBudgetNameTheLargestLightsAndCountTheRest) {
  Box box;
  scene::Scene scene = box_scene({box});
  for (int i = 0; i < 200; ++i)
    scene.lights.push_back(make_light("spot" + std::to_string(i), scene::LightType::spot, i == 123 ? 1024 : 256));
  passes::ShadowMaps maps(ctx(), shaders());
  passes::ShadowOptions options;
  options.map_budget_bytes = 64ull << 20;  // 199 AVSM-8 256^2 maps take 2 MiB each, the 1024^2 one 32 MiB
  try {
    maps.set_scene(scene, options);
    FAIL() << "no error for maps over the budget";
  } catch (const passes::ShadowBudgetError& e) {
    const std::string message = e.what();
    EXPECT_LT(message.size(), 600u) << message;
    EXPECT_NE(message.find(": light 123 'spot123' 32.00 MiB, light 0 'spot0' 2.00 MiB, light 1 'spot1' 2.00 MiB"),
              std::string::npos)
        << message;
    EXPECT_NE(message.find(" and 195 more lights (390.00 MiB); lower"), std::string::npos) << message;
    EXPECT_EQ(message.find("spot199"), std::string::npos) << message;
  }
}

// What one shader binding sees bounds what the shadows may take: a map budget above the
// storage buffer range is held to it (ShadowBudgetError), and the exact lists that
// uncompressed lights' lookups read, which no budget covers, are refused by the device
// limit check naming the lights and the setting, before anything is allocated.
TEST_F(LightMapsTest, MapsAndExactListsOverTheStorageRangeAreErrorsNamingTheLights) {
  Box box;
  scene::Scene scene = box_scene({box});
  const uint64_t range = ctx().info().max_storage_buffer_range;
  // An AVSM-8 map takes 32 bytes a texel: the smallest power-of-two side over the range.
  int resolution = 16;
  while (uint64_t(resolution) * uint64_t(resolution) * 32 <= range) resolution *= 2;
  if (resolution * 2 > 16384) GTEST_SKIP() << "no light resolution reaches this device's storage buffer range";
  scene.lights.push_back(make_light("sun", scene::LightType::directional, resolution));
  passes::ShadowMaps maps(ctx(), shaders());
  passes::ShadowOptions options;
  options.map_budget_bytes = range * 8;
  try {
    maps.set_scene(scene, options);
    FAIL() << "no error for a map over the storage buffer range";
  } catch (const passes::ShadowBudgetError& e) {
    EXPECT_NE(std::string(e.what()).find("(the device's storage buffer range): light 0 'sun'"), std::string::npos)
        << e.what();
  }

  // Uncompressed: no map, 4 bytes of list head a texel, so a side twice as large is over.
  scene.lights[0] = make_light("sun", scene::LightType::directional, resolution * 2, "uncompressed");
  try {
    maps.set_scene(scene, options);
    FAIL() << "no error for exact lists over the storage buffer range";
  } catch (const gpu::ResourceLimitError& e) {
    const std::string message = e.what();
    const uint64_t heads = uint64_t(resolution) * uint64_t(resolution) * 16;
    EXPECT_NE(message.find("'looked-up list heads' needs " + gpu::format_mib(heads) +
                           ", over the device's maxStorageBufferRange of " + gpu::format_mib(range)),
              std::string::npos)
        << message;
    const std::string side = std::to_string(resolution * 2);
    EXPECT_NE(message.find("--shadow-res"), std::string::npos) << message;
    EXPECT_NE(message.find("light 0 'sun' " + side + "x" + side), std::string::npos) << message;
  }
  // Half the side fits the range exactly.
  scene.lights[0].shadow.resolution = resolution;
  maps.set_scene(scene, options);
  EXPECT_EQ(maps.light_count(), 1u);
}

// ---- Directional maps fitted to the view ----

// A wide scene seen from close by: the map covers only what the camera sees (finer
// texels than a whole-scene map), and moving the camera by fractions of a texel gives
// the same transmittance at fixed receivers (whole-texel snapping: no shimmer).
TEST_F(LightMapsTest, ViewFittedMapIsFinerAndStableUnderSubTexelCameraMotion) {
  std::vector<Box> boxes;
  for (int i = 0; i < 5; ++i) {
    Box box;
    box.origin = glm::vec3(-16.0f + 8.0f * float(i), 0.0f, -0.75f);  // a 34 m row
    boxes.push_back(box);
  }
  scene::Scene scene = box_scene(boxes);
  scene::Light sun = make_light("sun", scene::LightType::directional, 128);
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  sun.shadow.distance = 6.0f;
  scene.lights.push_back(sun);
  const Box& middle = boxes[2];
  // Receivers under the middle box (the camera looks at it): nine in its shadow, then
  // 21 across the edge of its shadow, where a map that moved by part of a texel would
  // filter differently (what shimmers on screen).
  std::vector<glm::vec3> probes;
  for (int i = 0; i < 9; ++i)
    probes.push_back(middle.centre() + sun.direction * (1.4f + 0.05f * float(i)) + glm::vec3(0.05f * float(i - 4), 0, 0));
  const glm::vec3 edge = middle.centre() + sun.direction * 1.4f - glm::vec3(middle.centre().x - middle.low().x, 0, 0);
  for (int i = 0; i <= 20; ++i) probes.push_back(edge + glm::vec3(0.02f * float(i - 10), 0, 0));
  scene::Camera camera;
  camera.position = middle.centre() + glm::vec3(0.0f, 1.5f, 4.0f);
  camera.target = middle.centre();
  camera.far_plane = 50.0f;
  scene.cameras = {camera};
  renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
  renderer.set_probes(probes);
  const std::vector<float> first = render_probes(ctx(), renderer, camera).at(0);
  const passes::LightView fitted = renderer.shadows().light_views().at(0);
  const passes::LightView whole = passes::make_light_view(sun, scene.bounds, 128);
  EXPECT_LT(fitted.texel_size_base, 0.5f * whole.texel_size_base);
  const std::vector<glm::vec3> inside(probes.begin(), probes.begin() + 9);
  const ProbeError e = probe_error(boxes, sun, inside, first);
  EXPECT_LT(e.max, 0.03f);
  EXPECT_EQ(e.shadowed, 9);
  float worst = 0.0f;
  for (float texels : {0.3f, 0.7f, 2.4f}) {
    scene::Camera moved = camera;
    const glm::vec3 shift = glm::vec3(1.0f, 0.0f, 0.5f) * (texels * fitted.texel_size_base);
    moved.position += shift;
    moved.target += shift;
    const std::vector<float> again = render_probes(ctx(), renderer, moved, 1).at(0);
    for (size_t i = 0; i < probes.size(); ++i) worst = std::max(worst, std::abs(again[i] - first[i]));
  }
  std::cout << "[ view fit    ] texel " << fitted.texel_size_base << " m (whole scene: " << whole.texel_size_base
            << " m); mean error " << e.mean << ", largest change under camera motion " << worst << "\n";
  EXPECT_LT(worst, 1e-4f);
}

// Three cascades along the view: finer near the camera, and receivers near and far
// both in shadow as integrated.
TEST_F(LightMapsTest, CascadesSplitTheViewAndShadowNearAndFar) {
  std::vector<Box> boxes;
  for (float z : {-2.0f, -11.6f, -20.0f}) {  // the middle one straddles the end of cascade 1
    Box box;
    box.origin = glm::vec3(-0.75f, 0.0f, z);
    boxes.push_back(box);
  }
  scene::Scene scene = box_scene(boxes);
  scene::Light sun = make_light("sun", scene::LightType::directional, 64);
  sun.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  sun.shadow.cascades = 3;
  sun.shadow.distance = 30.0f;
  scene.lights.push_back(sun);
  scene::Camera camera;
  camera.position = glm::vec3(0.0f, 1.0f, 1.0f);
  camera.target = glm::vec3(0.0f, 0.5f, -20.0f);
  camera.far_plane = 40.0f;
  scene.cameras = {camera};
  std::vector<glm::vec3> probes;
  for (const Box& box : boxes) probes.push_back(box.centre() + sun.direction * 1.5f);
  // Under the middle box along the view, clear of its edges (where texels of 0.3 m blur
  // the shadow): across the end of cascade 1 (12.3 m from the camera), where it blends
  // into cascade 2.
  for (int i = 0; i <= 8; ++i)
    probes.push_back(glm::vec3(boxes[1].centre().x, boxes[1].centre().y, boxes[1].low().z + 0.35f + 0.1f * float(i)) +
                     sun.direction * 1.5f);
  renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
  renderer.set_probes(probes);
  const std::vector<float> got = render_probes(ctx(), renderer, camera).at(0);
  const std::vector<passes::LightView> cascades = renderer.shadows().map_views(0);
  ASSERT_EQ(cascades.size(), 3u);
  EXPECT_LT(cascades[0].texel_size_base, cascades[2].texel_size_base);
  EXPECT_EQ(renderer.shadows().frame_stats().at(0).map_kind, "cascades");
  const ProbeError e = probe_error(boxes, sun, probes, got);
  std::cout << "[ cascades    ] texels " << cascades[0].texel_size_base << ", " << cascades[1].texel_size_base << ", "
            << cascades[2].texel_size_base << " m; max error " << e.max << "\n";
  EXPECT_EQ(e.shadowed, int(probes.size()));
  EXPECT_LT(e.max, 0.03f);
}

// ---- Soft surface shadows ----

// A box's shadow edge on receivers across its edge: without a kernel
// the surface lookups step from texel to texel; box and Gaussian kernels turn the edge
// into a ramp as wide as the kernel, whose values rise steadily, and leave the fully
// shadowed and fully lit receivers as they are.
TEST_F(LightMapsTest, SurfaceKernelsTurnAShadowEdgeIntoARamp) {
  Box box;
  box.voxels = 24;
  const std::vector<Box> boxes = {box};
  struct Case {
    scene::ShadowKernel kernel;
    int radius;
  };
  const Case cases[] = {{scene::ShadowKernel::none, 1}, {scene::ShadowKernel::box, 2}, {scene::ShadowKernel::gaussian, 2}};
  std::vector<std::vector<float>> edges;
  for (const Case& c : cases) {
    scene::Scene scene = box_scene(boxes);
    scene::Light sun = make_light("sun", scene::LightType::directional, 32);
    sun.direction = glm::vec3(0.0f, -1.0f, 0.0f);
    sun.shadow.fit = scene::ShadowFit::scene;
    sun.shadow.filter = scene::ShadowFilter::point;  // the steps the kernels must remove
    sun.shadow.kernel = c.kernel;
    sun.shadow.kernel_radius = c.radius;
    scene.lights.push_back(sun);
    // Receivers on a floor below the box, facing up, across its x = low edge.
    std::vector<glm::vec3> points, normals;
    for (int i = 0; i <= 80; ++i) {
      points.emplace_back(box.low().x - 0.6f + 1.2f * float(i) / 80.0f, box.low().y - 0.5f, box.centre().z);
      normals.emplace_back(0.0f, 1.0f, 0.0f);
    }
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
    renderer.set_surface_probes(points, normals);
    edges.push_back(render_probes(ctx(), renderer, scene.cameras.front()).at(0));
  }
  const float texel = passes::make_light_view(make_light("sun", scene::LightType::directional, 32), box_scene(boxes).bounds, 32)
                          .texel_size_base;
  for (size_t k = 0; k < edges.size(); ++k) {
    const std::vector<float>& t = edges[k];
    int distinct_steps = 0;  // jumps between neighbours larger than a tenth of the edge
    float largest_jump = 0.0f;
    for (size_t i = 1; i < t.size(); ++i) {
      const float jump = std::abs(t[i] - t[i - 1]);
      largest_jump = std::max(largest_jump, jump);
      distinct_steps += jump > 0.1f * (t.front() - t.back());
      EXPECT_LE(t[i], t[i - 1] + 1e-4f) << "kernel " << k << ": the edge rises at receiver " << i;
    }
    std::cout << "[ kernel      ] " << scene::to_string(cases[k].kernel) << " r" << cases[k].radius << ": lit " << t.front()
              << ", shadowed " << t.back() << ", largest jump between receivers 1.5 cm apart " << largest_jump
              << " (texel " << texel << " m)\n";
    EXPECT_NEAR(t.front(), 1.0f, 1e-3f);
    EXPECT_NEAR(t.back(), std::exp(-kSigma * float(box.voxels) * kVoxel), 0.01f);  // through the whole box
    if (k == 0) {
      EXPECT_GT(largest_jump, 0.3f);  // point lookups: the edge is one step
    } else {
      EXPECT_LT(largest_jump, 0.1f);  // a ramp over the kernel's width
      EXPECT_EQ(distinct_steps, 0);
    }
  }
}

// ---- Clustered maps ----

// Two boxes 20 m apart under one sun: two clusters, each map fitted to its box (texels
// far finer than a map around both), the product of the two matching the integrated
// transmittance behind either box, built from lists and in fixed memory.
TEST_F(LightMapsTest, ClustersFitAMapToEachGroupOfCasters) {
  Box left, right;
  left.origin = glm::vec3(-10.0f, 0.0f, -0.75f);
  right.origin = glm::vec3(10.0f, 0.0f, -0.75f);
  const std::vector<Box> boxes = {left, right};
  for (scene::ShadowBuild build : {scene::ShadowBuild::lists, scene::ShadowBuild::fixed}) {
    scene::Scene scene = box_scene(boxes);
    scene::Light sun = make_light("sun", scene::LightType::directional, 64);
    sun.direction = glm::normalize(glm::vec3(0.1f, -1.0f, 0.15f));
    sun.shadow.fit = scene::ShadowFit::scene;
    sun.shadow.clusters = 4;
    sun.shadow.build = build;
    scene.lights.push_back(sun);
    std::vector<glm::vec3> probes;
    for (const Box& box : boxes)
      for (float t : {1.3f, 1.6f}) probes.push_back(box.centre() + sun.direction * t + glm::vec3(0.1f * t, 0, 0));
    renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
    renderer.set_probes(probes);
    const std::vector<float> got = render_probes(ctx(), renderer, scene.cameras.front()).at(0);
    const passes::LightShadowStats& stats = renderer.shadows().frame_stats().at(0);
    EXPECT_EQ(stats.map_kind, "clusters");
    EXPECT_EQ(stats.maps, 2u);
    const std::vector<passes::LightView> clusters = renderer.shadows().map_views(0);
    const passes::LightView single = passes::make_light_view(sun, scene.bounds, 64);
    for (const passes::LightView& view : clusters) EXPECT_LT(view.texel_size_base, 0.2f * single.texel_size_base);
    const ProbeError e = probe_error(boxes, sun, probes, got);
    std::cout << "[ clusters    ] " << scene::to_string(build) << ": texel " << clusters[0].texel_size_base
              << " m (one map: " << single.texel_size_base << " m); max error " << e.max << "\n";
    EXPECT_EQ(e.shadowed, int(probes.size()));
    EXPECT_LT(e.max, 0.03f) << scene::to_string(build);
  }
}

}  // namespace
}  // namespace light_maps_test
}  // namespace avsm
