// The viewer's CPU-side logic, without a window: camera control, picking, the
// light texel a point falls in, scene overrides, the --control commands, the
// panel's map summary and the window's layout (panel column and 3D view).
#include <gtest/gtest.h>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "passes/shadows/light_view.h"
#include "passes/frame/view.h"
#include "viewer/camera_controller.h"
#include "viewer/control_commands.h"
#include "viewer/panel.h"
#include "viewer/scene_overrides.h"
#include "renderer/scene_picking.h"
#include "viewer/texel_inspector.h"
#include "viewer/timeline.h"
#include "viewer/view_layout.h"

namespace avsm::viewer {
using renderer::pick_point;
using renderer::PickedPoint;

void PrintTo(const PixelRect& r, std::ostream* out) {
  *out << r.width << "x" << r.height << " at (" << r.x << ", " << r.y << ")";
}

namespace {

scene::Camera start_camera() {
  scene::Camera camera;
  camera.position = {0.0f, 1.0f, 5.0f};
  camera.target = {0.0f, 1.0f, 0.0f};
  return camera;
}

float distance_to_target(const scene::Camera& c) { return glm::length(c.position - c.target); }

TEST(CameraController, UntouchedCameraIsTheStartCamera) {
  CameraController controller(start_camera());
  EXPECT_FALSE(controller.update({}));
  EXPECT_EQ(controller.camera().position, start_camera().position);
  EXPECT_EQ(controller.camera().target, start_camera().target);
}

TEST(CameraController, OrbitKeepsTheTargetAndDistance) {
  CameraController controller(start_camera());
  ASSERT_TRUE(controller.update({.mouse_delta = {120.0f, -40.0f}, .rotate = true}));
  EXPECT_EQ(controller.camera().target, start_camera().target);
  EXPECT_NEAR(distance_to_target(controller.camera()), 5.0f, 1e-4f);
  // Dragging right moves the camera to the left of where it was (-x seen from +z).
  EXPECT_LT(controller.camera().position.x, 0.0f);
}

TEST(CameraController, OrbitStopsShortOfThePole) {
  CameraController controller(start_camera());
  controller.update({.mouse_delta = {0.0f, 5000.0f}, .rotate = true});  // far past straight down
  const glm::vec3 view = glm::normalize(controller.camera().target - controller.camera().position);
  EXPECT_GT(glm::length(glm::cross(view, glm::vec3(0, 1, 0))), 0.01f);
  EXPECT_NEAR(distance_to_target(controller.camera()), 5.0f, 1e-3f);
}

TEST(CameraController, WheelZoomsTowardsTheTarget) {
  CameraController controller(start_camera());
  controller.update({.scroll = 2.0f});
  EXPECT_NEAR(distance_to_target(controller.camera()), 5.0f * 0.81f, 1e-4f);
}

TEST(CameraController, PanMovesCameraAndTargetTogether) {
  CameraController controller(start_camera());
  controller.update({.mouse_delta = {50.0f, 0.0f}, .pan_or_look = true, .viewport_height = 500.0f});
  const scene::Camera& c = controller.camera();
  EXPECT_NEAR(c.position.x - start_camera().position.x, c.target.x - start_camera().target.x, 1e-5f);
  EXPECT_LT(c.target.x, 0.0f);  // the scene follows the mouse to the right: the camera moves left
}

TEST(CameraController, FlyMovesForwardAndLooks) {
  CameraController controller(start_camera());
  controller.mode = CameraMode::fly;
  controller.update({.move = {0.0f, 0.0f, 1.0f}, .seconds = 1.0f});
  EXPECT_NEAR(controller.camera().position.z, 5.0f - controller.fly_speed, 1e-4f);
  controller.update({.mouse_delta = {100.0f, 0.0f}, .pan_or_look = true});
  EXPECT_GT(controller.camera().target.x, controller.camera().position.x);  // looked right
}

// A 2x2 quad on the plane z = 0, facing the camera at z = 5.
scene::Scene quad_scene() {
  scene::Scene scene;
  scene::Mesh quad;
  quad.name = "quad";
  quad.positions = {{-1, 0, 0}, {1, 0, 0}, {1, 2, 0}, {-1, 2, 0}};
  quad.indices = {0, 1, 2, 0, 2, 3};
  for (const glm::vec3& p : quad.positions) quad.bounds.extend(p);
  scene.meshes.push_back(quad);
  scene.cameras.push_back(start_camera());
  return scene;
}

TEST(ScenePicking, CentrePixelHitsTheQuadInFrontOfTheCamera) {
  const scene::Scene scene = quad_scene();
  const passes::View view = passes::make_view(scene.cameras[0], 64, 64);
  const std::optional<PickedPoint> hit = pick_point(scene, view, {31.5f, 31.5f});
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->world.x, 0.0f, 1e-3f);
  EXPECT_NEAR(hit->world.y, 1.0f, 1e-3f);
  EXPECT_NEAR(hit->world.z, 0.0f, 1e-4f);
  EXPECT_EQ(hit->what, "mesh 'quad'");
}

TEST(ScenePicking, RowZeroIsTheTopOfTheImage) {
  const passes::View view = passes::make_view(start_camera(), 64, 64);
  EXPECT_GT(pixel_ray(view, {32, 0}).direction.y, 0.0f);
  EXPECT_LT(pixel_ray(view, {32, 63}).direction.y, 0.0f);
  EXPECT_GT(pixel_ray(view, {63, 32}).direction.x, 0.0f);
}

TEST(ScenePicking, MissIsNothing) {
  const scene::Scene scene = quad_scene();
  const passes::View view = passes::make_view(scene.cameras[0], 64, 64);
  EXPECT_FALSE(pick_point(scene, view, {0, 0}));  // the corner looks past the quad
}

// The texel centre's ray (as avsm-capture --plot-texel builds it) maps back to that texel.
TEST(LightTexel, TexelCentreRayMapsBackToItsTexel) {
  scene::Light sun;
  sun.direction = glm::normalize(glm::vec3(0.3f, -1.0f, 0.2f));
  scene::Bounds casters;
  casters.extend(glm::vec3(-2.0f));
  casters.extend(glm::vec3(2.0f));
  const passes::LightView view = passes::make_light_view(sun, casters, 64);
  for (glm::uvec2 texel : {glm::uvec2(0, 0), glm::uvec2(10, 50), glm::uvec2(63, 63)}) {
    const glm::vec2 ndc = (glm::vec2(texel) + 0.5f) / 64.0f * 2.0f - 1.0f;
    const glm::vec4 p = view.world_from_light * glm::vec4(ndc, 0.5f, 1.0f);
    const std::optional<glm::uvec2> found = light_texel(view, glm::vec3(p) / p.w);
    ASSERT_TRUE(found);
    EXPECT_EQ(*found, texel);
  }
  EXPECT_FALSE(light_texel(view, glm::vec3(100.0f, 0.0f, 0.0f)));  // outside the map
}

TEST(SceneOverrides, OnlyTouchedFieldsChange) {
  scene::Scene scene;
  scene.lights.resize(2);
  scene.lights[0].intensity = 3.0f;
  scene.lights[1].shadow.nodes = 16;
  scene::HairGroom hair;
  hair.strand_opacity = {0.4f, 0.8f};
  hair.strand_width = {0.01f, 0.02f};
  scene.hair.push_back(hair);

  SceneOverrides overrides;
  overrides.light(0).technique = "uncompressed";
  overrides.light(0).enabled = false;
  overrides.light(0).direction = glm::vec3(0.0f, -2.0f, 0.0f);
  overrides.light(5).nodes = 4;  // a light the scene does not have: ignored
  overrides.hair_opacity_scale = 2.0f;
  overrides.hair_width_scale = 0.5f;
  overrides.apply(scene);

  EXPECT_EQ(scene.lights[0].shadow.technique, "uncompressed");
  EXPECT_EQ(scene.lights[0].intensity, 0.0f);
  EXPECT_EQ(scene.lights[0].direction, glm::vec3(0.0f, -1.0f, 0.0f));
  EXPECT_EQ(scene.lights[1].shadow.nodes, 16);
  EXPECT_FLOAT_EQ(scene.hair[0].strand_opacity[0], 0.8f);
  EXPECT_FLOAT_EQ(scene.hair[0].strand_opacity[1], 1.0f);  // clamped
  EXPECT_FLOAT_EQ(scene.hair[0].strand_width[1], 0.01f);
}

TEST(SceneOverrides, VolumeScatteringEditsAreClampedToTheSceneFilesRanges) {
  scene::Scene scene;
  scene.volumes.resize(2);
  SceneOverrides overrides;
  overrides.volume(0).multiple_scattering = scene::MultipleScattering{12, 0.0f, 1.5f};
  overrides.volume(0).sky_light = 9.0f;
  overrides.apply(scene);
  EXPECT_EQ(scene.volumes[0].multiple_scattering.octaves, 8);
  EXPECT_GT(scene.volumes[0].multiple_scattering.attenuation, 0.0f);
  EXPECT_FLOAT_EQ(scene.volumes[0].multiple_scattering.contribution, 1.0f);
  EXPECT_FLOAT_EQ(scene.volumes[0].sky_light, 4.0f);
  EXPECT_EQ(scene.volumes[1].multiple_scattering, scene::MultipleScattering{});  // untouched
  EXPECT_FLOAT_EQ(scene.volumes[1].sky_light, 1.0f);
}

// The fog switch: off removes every medium; on over a scene without fog adds a thin global
// one; the global medium's edits are clamped to the scene file's ranges, the boxes kept.
TEST(SceneOverrides, FogSwitchAndEdits) {
  scene::Scene scene;
  SceneOverrides overrides;
  overrides.fog.enabled = true;
  overrides.apply(scene);
  EXPECT_TRUE(scene.fog.enabled()) << "switched on over a scene without fog";
  scene::Scene fogged;
  fogged.fog.boxes.push_back({scene::Bounds{glm::vec3(0.0f), glm::vec3(1.0f)}, {.scattering = 0.5f}});
  overrides.fog = {.scattering = 300.0f, .absorption = -1.0f, .phase_g = 2.0f, .sky_light = 9.0f};
  overrides.apply(fogged);
  EXPECT_FLOAT_EQ(fogged.fog.global.scattering, 100.0f);
  EXPECT_FLOAT_EQ(fogged.fog.global.absorption, 0.0f);
  EXPECT_FLOAT_EQ(fogged.fog.global.phase_g, 0.95f);
  EXPECT_FLOAT_EQ(fogged.fog.sky_light, 4.0f);
  EXPECT_EQ(fogged.fog.boxes.size(), 1u);
  overrides.fog.enabled = false;
  overrides.apply(fogged);
  EXPECT_FALSE(fogged.fog.enabled()) << "switched off";
}

// An area light's size, radius and virtual lights, clamped; other lights ignore them.
TEST(SceneOverrides, AreaLightEditsAreClamped) {
  scene::Scene scene;
  scene.lights.resize(2);
  scene.lights[0].type = scene::LightType::rect;
  scene.lights[1].type = scene::LightType::spot;
  SceneOverrides overrides;
  overrides.light(0).size = glm::vec2(2.0f, -1.0f);
  overrides.light(0).virtual_lights = 1000;
  overrides.light(1).size = glm::vec2(3.0f);
  overrides.apply(scene);
  EXPECT_EQ(scene.lights[0].size, glm::vec2(2.0f, kMinAreaLightExtent));
  EXPECT_EQ(scene.lights[0].virtual_lights, scene::kMaxVirtualLights);
  EXPECT_EQ(scene.lights[1].size, glm::vec2(1.0f)) << "not an area light";
  scene.lights[0].type = scene::LightType::disk;
  overrides.light(0) = {};
  overrides.light(0).radius = 0.0f;
  overrides.light(0).virtual_lights = 0;
  overrides.apply(scene);
  EXPECT_FLOAT_EQ(scene.lights[0].radius, kMinAreaLightExtent);
  EXPECT_EQ(scene.lights[0].virtual_lights, 1);
  overrides.light(0).area_shape = scene::LightType::sphere;
  overrides.light(1).area_shape = scene::LightType::rect;
  overrides.apply(scene);
  EXPECT_EQ(scene.lights[0].type, scene::LightType::sphere);
  EXPECT_EQ(scene.lights[1].type, scene::LightType::spot) << "a spot light does not become an area light";
}

TEST(Timeline, PlaysSnapsToItsFramesLoopsOrStopsAtTheEnd) {
  Timeline timeline;
  EXPECT_FALSE(timeline.animated());
  timeline.play();
  EXPECT_FALSE(timeline.playing()) << "nothing to play";
  timeline.set_duration(2.0f);
  timeline.set_fps(10.0f);
  EXPECT_FALSE(timeline.advance(0.5)) << "paused: the playhead stays";
  timeline.play();
  EXPECT_FALSE(timeline.advance(0.05)) << "half a frame: the shown time stays";
  EXPECT_TRUE(timeline.advance(0.05));
  EXPECT_EQ(timeline.frame(), 1);
  EXPECT_FLOAT_EQ(timeline.time(), 0.1f);
  for (int i = 0; i < 9; ++i) timeline.advance(0.1);  // ten steps of 1/10 s land on frame 10, not 9
  EXPECT_EQ(timeline.frame(), 10);
  timeline.scrub(1.95f);
  EXPECT_FLOAT_EQ(timeline.time(), 1.9f) << "snapped down to its frame";
  timeline.advance(0.2);  // past the end: looping wraps round
  EXPECT_TRUE(timeline.playing());
  EXPECT_EQ(timeline.frame(), 1);
  timeline.set_loop(false);
  timeline.advance(5.0);
  EXPECT_FALSE(timeline.playing()) << "without a loop it stops at the end";
  EXPECT_FLOAT_EQ(timeline.time(), 2.0f);
  timeline.play();
  EXPECT_EQ(timeline.frame(), 0) << "playing again from the end starts over";
  timeline.scrub(-3.0f);
  EXPECT_EQ(timeline.frame(), 0);
}

TEST(ControlCommands, ParsesEveryCommand) {
  EXPECT_EQ(parse_control_command("frame").kind, ControlCommand::Kind::frame);
  const ControlCommand inspect = parse_control_command("inspect 12,34");
  EXPECT_EQ(inspect.kind, ControlCommand::Kind::inspect);
  EXPECT_EQ(inspect.pixel, glm::vec2(12, 34));
  EXPECT_EQ(parse_control_command("screenshot out/a").directory, "out/a");
  const ControlCommand light = parse_control_command("light 1 technique dsm");
  EXPECT_EQ(light.light, 1u);
  EXPECT_EQ(light.field, "technique");
  EXPECT_EQ(light.value, "dsm");
  const ControlCommand cascades = parse_control_command("light 0 cascades 3");
  EXPECT_EQ(cascades.kind, ControlCommand::Kind::light);
  EXPECT_EQ(cascades.field, "cascades");
  EXPECT_EQ(cascades.value, "3");
  EXPECT_EQ(parse_control_command("light 2 clusters 4").field, "clusters");
  EXPECT_FLOAT_EQ(parse_control_command("exposure 0.5").exposure, 0.5f);
  const ControlCommand orbit = parse_control_command("orbit -2.5");
  EXPECT_EQ(orbit.kind, ControlCommand::Kind::orbit);
  EXPECT_FLOAT_EQ(orbit.degrees, -2.5f);
  const ControlCommand time = parse_control_command("time 1.25");
  EXPECT_EQ(time.kind, ControlCommand::Kind::time);
  EXPECT_FLOAT_EQ(time.seconds, 1.25f);
  EXPECT_FALSE(time.play.has_value());
  EXPECT_EQ(parse_control_command("play").play, std::optional<bool>(true));
  EXPECT_EQ(parse_control_command("pause").play, std::optional<bool>(false));
  EXPECT_EQ(parse_control_command("quit").kind, ControlCommand::Kind::quit);
}

TEST(ControlCommands, RejectsMalformedLinesWithAReason) {
  EXPECT_THROW(parse_control_command("jump"), std::invalid_argument);
  EXPECT_THROW(parse_control_command("inspect 12"), std::invalid_argument);
  EXPECT_THROW(parse_control_command("frame now"), std::invalid_argument);
  EXPECT_THROW(parse_control_command("light x technique avsm"), std::invalid_argument);
  EXPECT_THROW(parse_control_command("orbit"), std::invalid_argument);
  EXPECT_THROW(parse_control_command("orbit left"), std::invalid_argument);
  EXPECT_THROW(parse_control_command("orbit 400"), std::invalid_argument);
  EXPECT_THROW(parse_control_command("time"), std::invalid_argument);
  EXPECT_THROW(parse_control_command("play now"), std::invalid_argument);
  SceneOverrides overrides;
  EXPECT_THROW(set_light_field(overrides, 0, "technique", "best"), std::invalid_argument);
  EXPECT_THROW(set_light_field(overrides, 0, "colour", "red"), std::invalid_argument);
  set_light_field(overrides, 0, "sort", "off");
  EXPECT_EQ(overrides.lights[0].sort, false);
  // The scene file's ranges: cascades 1 to 4, clusters 0 (off) to 8.
  for (const char* bad : {"0", "5", "2.5", "many"})
    EXPECT_THROW(set_light_field(overrides, 0, "cascades", bad), std::invalid_argument) << bad;
  for (const char* bad : {"9", "-1", "all"})
    EXPECT_THROW(set_light_field(overrides, 0, "clusters", bad), std::invalid_argument) << bad;
  EXPECT_THROW(set_light_field(overrides, 0, "fit", "camera"), std::invalid_argument);
  EXPECT_THROW(set_light_field(overrides, 0, "layout", "sparse"), std::invalid_argument);
  EXPECT_THROW(set_light_field(overrides, 0, "kernel", "tent"), std::invalid_argument);
  EXPECT_FALSE(overrides.lights[0].cascades);  // a refused value sets nothing
  EXPECT_FALSE(overrides.lights[0].clusters);
}

TEST(ControlCommands, CascadesClustersFitLayoutAndKernelReachTheLight) {
  SceneOverrides overrides;
  set_light_field(overrides, 0, "cascades", "3");
  set_light_field(overrides, 1, "clusters", "4");
  set_light_field(overrides, 1, "fit", "scene");
  scene::Scene scene;
  scene.lights.resize(2);
  scene.lights[1].shadow.cascades = 2;  // untouched by light 1's edits
  overrides.apply(scene);
  EXPECT_EQ(scene.lights[0].shadow.cascades, 3);
  EXPECT_EQ(scene.lights[0].shadow.clusters, 0);
  EXPECT_EQ(scene.lights[0].shadow.fit, scene::ShadowFit::view);
  EXPECT_EQ(scene.lights[1].shadow.clusters, 4);
  EXPECT_EQ(scene.lights[1].shadow.cascades, 2);
  EXPECT_EQ(scene.lights[1].shadow.fit, scene::ShadowFit::scene);
  set_light_field(overrides, 1, "layout", "paged");
  set_light_field(overrides, 1, "kernel", "none");
  overrides.apply(scene);
  EXPECT_EQ(scene.lights[1].shadow.layout, scene::ShadowLayout::paged);
  EXPECT_EQ(scene.lights[1].shadow.kernel, scene::ShadowKernel::none);
  EXPECT_EQ(scene.lights[0].shadow.layout, scene::ShadowLayout::dense);
  set_light_field(overrides, 0, "clusters", "0");  // 0 is a value (off), not "unset"
  overrides.apply(scene);
  EXPECT_EQ(overrides.lights[0].clusters, 0);
}

TEST(ControlCommands, LightMovesReachTheLight) {
  SceneOverrides overrides;
  set_light_field(overrides, 0, "direction", "0,-2,0");
  set_light_field(overrides, 1, "position", "1.5,2,-3");
  scene::Scene scene;
  scene.lights.resize(2);
  overrides.apply(scene);
  EXPECT_EQ(scene.lights[0].direction, glm::vec3(0, -1, 0));  // normalised
  EXPECT_EQ(scene.lights[1].position, glm::vec3(1.5f, 2, -3));
  for (const char* bad : {"1,2", "1,2,3,4", "1,x,3", "nan,0,0", "0,0,inf", ""})
    EXPECT_THROW(set_light_field(overrides, 1, "position", bad), std::invalid_argument) << bad;
  EXPECT_THROW(set_light_field(overrides, 0, "direction", "0,0,0"), std::invalid_argument);
  EXPECT_EQ(overrides.lights[1].position, glm::vec3(1.5f, 2, -3));  // a refused value changes nothing
}

TEST(Panel, MapSummaryNamesKindCountAndBudgetLowering) {
  passes::LightShadowStats single;
  single.resolution = 1024;
  EXPECT_EQ(map_summary(single), "single map, 1024^2");
  passes::LightShadowStats cube;
  cube.maps = 6, cube.map_kind = "cube", cube.resolution = 256;
  EXPECT_EQ(map_summary(cube), "cube: 6 maps, 256^2");
  passes::LightShadowStats cascades;
  cascades.maps = 3, cascades.map_kind = "cascades", cascades.resolution = 512, cascades.lowered_from = 2048;
  EXPECT_EQ(map_summary(cascades), "cascades: 3 maps, 512^2 (lowered from 2048 to fit the map budget)");
}

// The panel's column and the view side by side: no overlap, no gap, the whole window.
void expect_docked(const ViewLayout& layout, glm::uvec2 window) {
  const PixelRect &panel = layout.panel, &view = layout.view;
  EXPECT_EQ(panel.x, 0u);
  EXPECT_EQ(panel.y, 0u);
  EXPECT_EQ(panel.height, window.y);
  EXPECT_EQ(view.x, panel.x + panel.width) << "the view starts where the panel ends";
  EXPECT_EQ(view.y, 0u);
  EXPECT_EQ(view.height, window.y);
  EXPECT_EQ(view.x + view.width, window.x) << "the view reaches the right edge";
  // Every pixel is in exactly one of them.
  for (uint32_t x = 0; x < window.x; x += std::max(window.x / 97, 1u))
    for (uint32_t y = 0; y < window.y; y += std::max(window.y / 53, 1u)) {
      const glm::vec2 pixel(x, y);
      EXPECT_NE(panel.contains(pixel), view.contains(pixel)) << x << ", " << y;
    }
}

TEST(ViewLayout, PanelIsDockedLeftAndTheViewKeepsTheRest) {
  for (const glm::uvec2 window : {glm::uvec2(1280, 720), glm::uvec2(960, 540), glm::uvec2(1920, 1080),
                                  glm::uvec2(320, 180), glm::uvec2(160, 90), glm::uvec2(96, 54), glm::uvec2(7, 3)}) {
    SCOPED_TRACE(testing::Message() << window.x << "x" << window.y);
    const ViewLayout layout = layout_for(window);
    expect_docked(layout, window);
    EXPECT_FALSE(layout.view.empty());
  }
}

TEST(ViewLayout, PanelIs420WideOrAtMost40PercentOfTheWindow) {
  EXPECT_EQ(layout_for({1280, 720}).panel.width, 420u);
  EXPECT_EQ(layout_for({1280, 720}).view, (PixelRect{420, 0, 860, 720}));
  EXPECT_EQ(layout_for({1920, 1080}).panel.width, 420u);
  EXPECT_EQ(layout_for({1050, 600}).panel.width, 420u);  // exactly 40%
  // Narrower windows: the panel narrows, the view keeps 60% of the width and all the height.
  EXPECT_EQ(layout_for({960, 540}).view, (PixelRect{384, 0, 576, 540}));
  // The size the tests run the viewer at (tests/viewer/CMakeLists.txt captures at the view's size).
  EXPECT_EQ(layout_for({320, 180}).view, (PixelRect{128, 0, 192, 180}));
  EXPECT_EQ(layout_for({160, 90}).view, (PixelRect{64, 0, 96, 90}));
  EXPECT_EQ(layout_for({1, 1}).view, (PixelRect{0, 0, 1, 1}));  // no room for a panel: all view
  for (uint32_t width = 1; width <= 2000; width += 13) {
    const ViewLayout layout = layout_for({width, 100});
    EXPECT_GE(layout.view.width * 100, width * 60) << width;
    EXPECT_LE(layout.panel.width, 420u) << width;
  }
}

TEST(ViewLayout, MinimisedWindowHasNothingToShow) {
  const ViewLayout layout = layout_for({0, 0});
  EXPECT_TRUE(layout.view.empty());
  EXPECT_TRUE(layout.panel.empty());
  EXPECT_FALSE(layout.in_view({0.0f, 0.0f}));
}

TEST(ViewLayout, HiDpiPanelIs420WindowUnits) {
  // A 1280x720 window on a 2x screen: a 2560x1440 framebuffer.
  const ViewLayout layout = layout_for({2560, 1440}, {2.0f, 2.0f});
  expect_docked(layout, {2560, 1440});
  EXPECT_EQ(layout.panel.width, 840u);
  EXPECT_EQ(layout.panel_position(), glm::vec2(0.0f));
  EXPECT_EQ(layout.panel_size(), glm::vec2(420.0f, 720.0f));  // ImGui's units
  EXPECT_EQ(layout.view, (PixelRect{840, 0, 1720, 1440}));
}

TEST(ViewLayout, WindowPositionsBecomeViewPixels) {
  const ViewLayout layout = layout_for({960, 540});  // view: 576x540 at x 384
  EXPECT_EQ(layout.view_pixel({384.0f, 0.0f}), glm::vec2(0.0f, 0.0f));
  EXPECT_EQ(layout.view_pixel({384.7f, 10.2f}), glm::vec2(0.0f, 10.0f));  // the pixel the cursor is over
  EXPECT_EQ(layout.view_pixel({959.0f, 539.0f}), glm::vec2(575.0f, 539.0f));
  EXPECT_TRUE(layout.in_view({384.0f, 0.0f}));
  EXPECT_TRUE(layout.in_view({959.9f, 539.9f}));
  EXPECT_FALSE(layout.in_view({383.9f, 100.0f})) << "over the panel";
  EXPECT_FALSE(layout.in_view({960.0f, 100.0f})) << "right of the window";
  EXPECT_FALSE(layout.in_view({500.0f, -1.0f})) << "above the window";
  EXPECT_FALSE(layout.in_view({-3.4e38f, -3.4e38f})) << "ImGui's 'no mouse'";
  // HiDPI: window units times the scale, then relative to the view.
  const ViewLayout hidpi = layout_for({2560, 1440}, {2.0f, 2.0f});  // view at x 840 pixels = 420 units
  EXPECT_EQ(hidpi.view_pixel({420.0f, 0.0f}), glm::vec2(0.0f, 0.0f));
  EXPECT_EQ(hidpi.view_pixel({420.5f, 0.5f}), glm::vec2(1.0f, 1.0f));
  EXPECT_EQ(hidpi.view_pixel({1279.9f, 719.9f}), glm::vec2(1719.0f, 1439.0f));
  EXPECT_FALSE(hidpi.in_view({419.9f, 10.0f}));
}

// A click on the view picks through the view pixel under it, with the view's own
// aspect: the quad's centre, in front of the camera, is under the view's centre.
TEST(ViewLayout, ClickOnTheViewsCentrePicksTheSceneInFrontOfTheCamera) {
  const scene::Scene scene = quad_scene();
  const ViewLayout layout = layout_for({960, 540});
  const passes::View view = passes::make_view(scene.cameras[0], layout.view.width, layout.view.height);
  const glm::vec2 centre = glm::vec2(layout.view.x, layout.view.y) + glm::vec2(layout.view.width, layout.view.height) * 0.5f;
  const glm::vec2 pixel = layout.view_pixel(centre);
  EXPECT_EQ(pixel, glm::vec2(288.0f, 270.0f));
  const std::optional<PickedPoint> hit = pick_point(scene, view, pixel);
  ASSERT_TRUE(hit);
  EXPECT_NEAR(hit->world.x, 0.0f, 0.01f);
  EXPECT_NEAR(hit->world.y, 1.0f, 0.01f);
  // The same click read as a window pixel (the panel's width off) would miss the quad's middle.
  const std::optional<PickedPoint> unshifted = pick_point(scene, view, centre);
  EXPECT_FALSE(unshifted && std::abs(unshifted->world.x) < 0.1f);
}

}  // namespace
}  // namespace avsm::viewer
