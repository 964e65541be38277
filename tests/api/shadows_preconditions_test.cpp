// The embedding API's preconditions (avsm/shadows.h), checked without a device through
// Shadows::check_lights and Shadows::check_frame: valid data passes, and each violation
// throws std::invalid_argument naming the function, the argument and the problem.
#include <gtest/gtest.h>

#include <cmath>
#include <cstdint>
#include <functional>
#include <limits>
#include <string>

#include "avsm/shadows.h"
#include "shared/volume.h"

namespace avsm {
namespace shadows_preconditions_test {  // one per file: test targets are unity builds
namespace {

constexpr float kNaN = std::numeric_limits<float>::quiet_NaN();
constexpr float kInf = std::numeric_limits<float>::infinity();

// A non-null handle the checks only compare against VK_NULL_HANDLE (nothing is drawn).
template <class Handle>
Handle fake(uintptr_t value) {
  return (Handle)value;
}

// Runs `call` and expects std::invalid_argument whose message starts with `prefix` and
// contains every one of `parts`.
void expect_rejected(const std::function<void()>& call, const std::string& prefix,
                     std::initializer_list<std::string> parts) {
  try {
    call();
    ADD_FAILURE() << "accepted; expected a message with " << *parts.begin();
  } catch (const std::invalid_argument& e) {
    const std::string message = e.what();
    EXPECT_EQ(message.rfind(prefix, 0), 0u) << message;
    for (const std::string& part : parts) EXPECT_NE(message.find(part), std::string::npos) << message;
  }
}

// ---- set_lights ------------------------------------------------------------------------

struct LightsCase {
  std::vector<Light> lights;
  Bounds bounds;
  std::vector<CasterObject> objects;
};

LightsCase valid_lights() {
  LightsCase c;
  Light sun;
  sun.name = "sun";
  sun.direction = {0.3f, -1.0f, 0.2f};
  Light spot;
  spot.name = "key";
  spot.type = LightType::spot;
  spot.position = {0.0f, 4.0f, 0.0f};
  spot.outer_cone_radians = 0.6f;
  spot.range = 20.0f;
  spot.clusters = 2;
  Light lamp;
  lamp.name = "lamp";
  lamp.type = LightType::point;
  lamp.position = {1.0f, 2.0f, 3.0f};
  lamp.direction = {0.0f, 0.0f, 0.0f};  // unused by point lights
  Light cascaded;
  cascaded.name = "cascaded";
  cascaded.fit_to_view = true;
  cascaded.cascades = 4;
  cascaded.shadow_distance = 30.0f;
  cascaded.filter = ShadowFilter::trilinear;
  Light softbox;
  softbox.name = "softbox";
  softbox.type = LightType::rect;
  softbox.position = {0.0f, 2.5f, 0.0f};
  softbox.size = {1.0f, 0.5f};
  softbox.virtual_lights = 64;
  softbox.resolution = 256;
  c.lights = {sun, spot, lamp, cascaded, softbox};
  c.bounds.extend(glm::vec3(-5.0f, 0.0f, -5.0f));
  c.bounds.extend(glm::vec3(5.0f, 3.0f, 5.0f));
  CasterObject box;
  box.name = "box";
  box.bounds = c.bounds;
  c.objects = {box};
  return c;
}

void expect_lights_rejected(const std::function<void(LightsCase&)>& change, std::initializer_list<std::string> parts) {
  LightsCase c = valid_lights();
  change(c);
  expect_rejected([&] { Shadows::check_lights(c.lights, c.bounds, c.objects); }, "avsm::Shadows::set_lights: ", parts);
}

TEST(ShadowsPreconditions, ValidLightsPass) {
  const LightsCase c = valid_lights();
  EXPECT_NO_THROW(Shadows::check_lights(c.lights, c.bounds, c.objects));
  EXPECT_NO_THROW(Shadows::check_lights({}, Bounds()));  // no lights, no bounds: a unit box
}

TEST(ShadowsPreconditions, LightDirectionAndPositionMustBeFinite) {
  expect_lights_rejected([](LightsCase& c) { c.lights[0].direction = {kNaN, -1.0f, 0.0f}; },
                         {"light 0 'sun'", "direction (nan, -1, 0)", "finite and not zero"});
  expect_lights_rejected([](LightsCase& c) { c.lights[0].direction = {0.0f, 0.0f, 0.0f}; }, {"light 0 'sun'", "direction"});
  expect_lights_rejected([](LightsCase& c) { c.lights[1].direction = {0.0f, -kInf, 0.0f}; }, {"light 1 'key'", "direction"});
  expect_lights_rejected([](LightsCase& c) { c.lights[1].position = {0.0f, kInf, 0.0f}; },
                         {"light 1 'key'", "position (0, inf, 0) is not finite"});
  expect_lights_rejected([](LightsCase& c) { c.lights[2].position = {kNaN, 0.0f, 0.0f}; }, {"light 2 'lamp'", "position"});
}

TEST(ShadowsPreconditions, LightAnglesAndRangesMustBeInRange) {
  for (float cone : {0.0f, -0.2f, 1.6f, kNaN})
    expect_lights_rejected([=](LightsCase& c) { c.lights[1].outer_cone_radians = cone; },
                           {"light 1 'key'", "outer_cone_radians", "(0, 1.55)"});
  for (float range : {-1.0f, kInf, kNaN})
    expect_lights_rejected([=](LightsCase& c) { c.lights[1].range = range; }, {"light 1 'key'", "range", ">= 0"});
  for (float distance : {-0.5f, kNaN})
    expect_lights_rejected([=](LightsCase& c) { c.lights[3].shadow_distance = distance; },
                           {"light 3 'cascaded'", "shadow_distance"});
  expect_lights_rejected([](LightsCase& c) { c.lights[0].type = static_cast<LightType>(7); },
                         {"light 0 'sun'", "type 7 is not a LightType"});
  expect_lights_rejected([](LightsCase& c) { c.lights[0].filter = static_cast<ShadowFilter>(9); },
                         {"light 0 'sun'", "filter 9 is not a ShadowFilter"});
}

TEST(ShadowsPreconditions, ShadowSettingsMustBeInRange) {
  for (uint32_t nodes : {0u, 5u, 20u, std::numeric_limits<uint32_t>::max()})
    expect_lights_rejected([=](LightsCase& c) { c.lights[0].nodes = nodes; }, {"light 0 'sun'", "AVSM nodes; use 4, 8, 12 or 16"});
  for (uint32_t resolution : {0u, 16385u})
    expect_lights_rejected([=](LightsCase& c) { c.lights[0].resolution = resolution; },
                           {"light 0 'sun'", "resolution " + std::to_string(resolution), "1..16384"});
  for (uint32_t cascades : {0u, 5u})
    expect_lights_rejected([=](LightsCase& c) { c.lights[3].cascades = cascades; }, {"light 3 'cascaded'", "cascades; use 1 to 4"});
  expect_lights_rejected([](LightsCase& c) { c.lights[1].cascades = 2; }, {"light 1 'key'", "cascades split a directional"});
  expect_lights_rejected([](LightsCase& c) { c.lights[1].clusters = 1000; }, {"light 1 'key'", "1000 clusters"});
  expect_lights_rejected([](LightsCase& c) { c.lights[2].clusters = 2; }, {"light 2 'lamp'", "clustered maps"});
}

// Area lights: their extent, their virtual lights, and what their batched build cannot do.
TEST(ShadowsPreconditions, AreaLightsMustBeMadeRight) {
  for (glm::vec2 size : {glm::vec2(0.0f, 1.0f), glm::vec2(1.0f, -1.0f), glm::vec2(kNaN, 1.0f)})
    expect_lights_rejected([=](LightsCase& c) { c.lights[4].size = size; }, {"light 4 'softbox'", "size", "> 0 both ways"});
  for (float radius : {0.0f, kInf})
    expect_lights_rejected([=](LightsCase& c) {
      c.lights[4].type = LightType::disk;
      c.lights[4].radius = radius;
    }, {"light 4 'softbox'", "radius", "> 0"});
  for (uint32_t count : {0u, 257u})
    expect_lights_rejected([=](LightsCase& c) { c.lights[4].virtual_lights = count; },
                           {"light 4 'softbox'", std::to_string(count) + " virtual lights; use 1 to 256"});
  expect_lights_rejected([](LightsCase& c) { c.lights[4].fixed_memory_build = true; },
                         {"light 4 'softbox'", "set shadow.build to \"lists\""});
  expect_lights_rejected([](LightsCase& c) { c.lights[4].paged = true; }, {"light 4 'softbox'", "paged"});
}

TEST(ShadowsPreconditions, BoundsMustBeFiniteOrUnset) {
  expect_lights_rejected([](LightsCase& c) { c.bounds.max.y = kNaN; }, {"casters_bounds", "not finite with min <= max"});
  expect_lights_rejected([](LightsCase& c) { c.bounds.min.x = -kInf; }, {"casters_bounds"});
  expect_lights_rejected([](LightsCase& c) { std::swap(c.bounds.min, c.bounds.max); }, {"casters_bounds"});
  expect_lights_rejected([](LightsCase& c) { c.objects[0].bounds.min.z = kNaN; }, {"objects[0] 'box'.bounds"});
  expect_lights_rejected([](LightsCase& c) { c.objects[0].count = 0; }, {"objects[0] 'box'", "count is 0"});
}

// ---- pass_list --------------------------------------------------------------------------

struct FrameCase {
  Camera camera;
  ShadowCasters casters;
  std::vector<CasterObject> objects;
};

// 100 vertices, 300 indices in two draws; 40 points, 32 segments, 8 strands; 3 volumes.
FrameCase valid_frame() {
  FrameCase f;
  f.camera.position = {0.0f, 2.0f, 6.0f};
  f.camera.height_pixels = 360;
  MeshCasters& m = f.casters.meshes;
  m.vertices = fake<VkBuffer>(0x10);
  m.vertices_size = 100 * sizeof(CasterVertex);
  m.indices = fake<VkBuffer>(0x20);
  m.indices_size = 300 * sizeof(uint32_t);
  m.draws = {{0, 150, 0}, {150, 150, 50}};
  m.draws[1].alpha = passes::CasterAlpha::mask;
  m.draws[1].alpha_cutoff = 0.5f;
  StrandCasters& s = f.casters.strands;
  s.points = fake<VkBuffer>(0x30);
  s.points_size = 40 * 16;
  s.segments = fake<VkBuffer>(0x40);
  s.segments_size = 32 * sizeof(StrandSegment);
  s.strands = fake<VkBuffer>(0x50);
  s.strands_size = 8 * sizeof(StrandParameters);
  s.segment_count = 16;
  s.first_segment = 16;
  VolumeCasters& v = f.casters.volumes;
  v.grids = fake<VkBuffer>(0x60);
  v.majorants = fake<VkBuffer>(0x70);
  v.parameters = fake<VkBuffer>(0x80);
  v.parameters_size = 3 * sizeof(shared::GpuVolume);
  v.volume_count = 3;
  CasterObject draw, hair, smoke;
  draw.kind = CasterObject::Kind::mesh_draw;
  draw.first = 1;
  hair.kind = CasterObject::Kind::strands;
  hair.first = 0;
  hair.count = 16;
  smoke.kind = CasterObject::Kind::volume;
  smoke.first = 2;
  f.objects = {draw, hair, smoke};
  return f;
}

void expect_frame_rejected(const std::function<void(FrameCase&)>& change, std::initializer_list<std::string> parts) {
  FrameCase f = valid_frame();
  change(f);
  expect_rejected([&] { Shadows::check_frame(f.camera, f.casters, f.objects); }, "avsm::Shadows::pass_list: ", parts);
}

TEST(ShadowsPreconditions, ValidFramePasses) {
  const FrameCase f = valid_frame();
  EXPECT_NO_THROW(Shadows::check_frame(f.camera, f.casters, f.objects));
  EXPECT_NO_THROW(Shadows::check_frame(Camera(), ShadowCasters()));  // nothing casts: no buffers needed
}

TEST(ShadowsPreconditions, CameraMustBeFiniteAndProper) {
  expect_frame_rejected([](FrameCase& f) { f.camera.position.x = kNaN; }, {"camera.position (nan, 2, 6) is not finite"});
  expect_frame_rejected([](FrameCase& f) { f.camera.forward = glm::vec3(0.0f); }, {"camera.forward", "not zero"});
  expect_frame_rejected([](FrameCase& f) { f.camera.forward.z = -kInf; }, {"camera.forward"});
  expect_frame_rejected([](FrameCase& f) { f.camera.up = glm::vec3(0.0f); }, {"camera.up", "not zero"});
  expect_frame_rejected([](FrameCase& f) { f.camera.up = {0.0f, 0.0f, 2.0f}; }, {"camera.up", "along camera.forward"});
  for (float fov : {0.0f, 3.2f, kNaN})
    expect_frame_rejected([=](FrameCase& f) { f.camera.vertical_fov_radians = fov; }, {"camera.vertical_fov_radians", "(0, pi)"});
  expect_frame_rejected([](FrameCase& f) { f.camera.height_pixels = 0; }, {"camera.height_pixels is 0"});
  for (float aspect : {0.0f, -1.0f, kInf})
    expect_frame_rejected([=](FrameCase& f) { f.camera.aspect = aspect; }, {"camera.aspect"});
  expect_frame_rejected([](FrameCase& f) { f.camera.near_plane = 0.0f; }, {"camera.near_plane 0", "0 < near_plane < far_plane"});
  expect_frame_rejected([](FrameCase& f) { f.camera.far_plane = 0.05f; }, {"far_plane 0.05"});
  expect_frame_rejected([](FrameCase& f) { f.camera.far_plane = kInf; }, {"far_plane inf"});
}

TEST(ShadowsPreconditions, MeshBuffersMustHoldTheDraws) {
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.vertices = VK_NULL_HANDLE; },
                        {"casters.meshes.vertices is VK_NULL_HANDLE"});
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.indices_size = 0; },
                        {"casters.meshes.indices_size is 0: an empty buffer"});
  // A host's packed float3 positions: not the CasterVertex layout.
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.vertices_size = 100 * 12 + 4; },
                        {"casters.meshes.vertices_size 1204 bytes is not a whole number of CasterVertex",
                         "stride " + std::to_string(sizeof(CasterVertex))});
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.indices_size = 598; }, {"indices_size 598", "uint32 (stride 4)"});
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.draws[1].index_count = 153; },
                        {"casters.meshes.draws[1]: indices 150..303 exceed the index buffer (1200 bytes = 300 indices at stride 4)"});
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.draws[0].first_index = std::numeric_limits<uint32_t>::max(); },
                        {"casters.meshes.draws[0]: indices 4294967295..4294967445 exceed"});
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.draws[0].index_count = 100; }, {"draws[0]: index_count 100", "multiple of 3"});
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.draws[1].vertex_offset = 100; },
                        {"draws[1]: vertex_offset 100 is past the vertex buffer",
                         "= 100 vertices at stride " + std::to_string(sizeof(CasterVertex))});
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.draws[1].alpha = static_cast<passes::CasterAlpha>(4); },
                        {"draws[1]: alpha 4 is not a CasterAlpha"});
  for (float cutoff : {-0.1f, 1.5f, kNaN})
    expect_frame_rejected([=](FrameCase& f) { f.casters.meshes.draws[1].alpha_cutoff = cutoff; }, {"draws[1]: alpha_cutoff", "[0, 1]"});
  expect_frame_rejected([](FrameCase& f) { f.casters.meshes.draws[0].alpha_factor = kNaN; }, {"draws[0]: alpha_factor nan"});
}

TEST(ShadowsPreconditions, StrandBuffersMustHoldTheSegments) {
  expect_frame_rejected([](FrameCase& f) { f.casters.strands.points = VK_NULL_HANDLE; }, {"casters.strands.points is VK_NULL_HANDLE"});
  // 41 vec3 points instead of vec4.
  expect_frame_rejected([](FrameCase& f) { f.casters.strands.points_size = 41 * 12; },
                        {"casters.strands.points_size 492 bytes is not a whole number of vec4 (stride 16)"});
  expect_frame_rejected([](FrameCase& f) { f.casters.strands.points_size = 16; }, {"holds 1 point"});
  expect_frame_rejected([](FrameCase& f) { f.casters.strands.strands_size = 0; }, {"casters.strands.strands_size is 0"});
  expect_frame_rejected([](FrameCase& f) { f.casters.strands.segments = VK_NULL_HANDLE; }, {"casters.strands.segments is VK_NULL_HANDLE"});
  expect_frame_rejected([](FrameCase& f) { f.casters.strands.segment_count = 17; },
                        {"casters.strands: segments 16..33 exceed the segment buffer (" +
                         std::to_string(32 * sizeof(StrandSegment)) + " bytes = 32 StrandSegment at stride " +
                         std::to_string(sizeof(StrandSegment)) + ")"});
}

TEST(ShadowsPreconditions, VolumeBuffersMustHoldTheVolumes) {
  expect_frame_rejected([](FrameCase& f) { f.casters.volumes.grids = VK_NULL_HANDLE; }, {"casters.volumes.grids is VK_NULL_HANDLE"});
  expect_frame_rejected([](FrameCase& f) { f.casters.volumes.majorants = VK_NULL_HANDLE; }, {"casters.volumes.majorants"});
  expect_frame_rejected([](FrameCase& f) { f.casters.volumes.volume_count = 4; },
                        {"casters.volumes: volume_count 4 exceeds the parameter buffer", "3 GpuVolume"});
  expect_frame_rejected([](FrameCase& f) { f.casters.volumes.parameters_size += 4; }, {"parameters_size", "GpuVolume"});
  expect_frame_rejected([](FrameCase& f) { f.casters.volumes.atlas = fake<VkImageView>(0x90); },
                        {"casters.volumes: the density atlas needs atlas, atlas_sampler and brick_slots"});
}

TEST(ShadowsPreconditions, ClusterObjectsMustLieWithinTheCasters) {
  expect_frame_rejected([](FrameCase& f) { f.objects[0].first = 2; },
                        {"the object 0 given to set_lights is mesh draws 2..3, but the casters have 2"});
  expect_frame_rejected([](FrameCase& f) { f.objects[1].count = 17; }, {"object 1", "strand segments 0..17", "have 16"});
  expect_frame_rejected([](FrameCase& f) { f.objects[2].first = 3; }, {"object 2", "volumes 3..4", "have 3"});
}

}  // namespace
}  // namespace shadows_preconditions_test
}  // namespace avsm
