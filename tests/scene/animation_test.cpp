// Keyframes: tracks (step, linear, cubic), the scene file's "animation" blocks on cameras,
// lights and models, and a loaded scene posed at a time; bad blocks name their JSON path.
#include "support.h"

#include "scene/animation.h"
#include "scene/scene.h"

#include <gmock/gmock.h>

namespace avsm::scene {
namespace animation_test {  // one per file: test targets are unity builds
namespace {

using ::testing::HasSubstr;
using testing::TempDir;

Track<1> track(std::vector<float> times, std::vector<float> values, Interpolation interpolation) {
  Track<1> t;
  t.times = std::move(times);
  for (float v : values) t.values.emplace_back(v);
  t.interpolation = interpolation;
  return t;
}

TEST(Track, StepLinearAndCubicBetweenKeysAndHeldOutside) {
  const std::vector<float> times = {0.0f, 1.0f, 3.0f}, values = {0.0f, 2.0f, 0.0f};
  const Track<1> step = track(times, values, Interpolation::step);
  const Track<1> linear = track(times, values, Interpolation::linear);
  const Track<1> cubic = track(times, values, Interpolation::cubic);
  EXPECT_FLOAT_EQ(step.sample(0.99f).x, 0.0f);
  EXPECT_FLOAT_EQ(step.sample(1.0f).x, 2.0f);
  EXPECT_FLOAT_EQ(linear.sample(0.5f).x, 1.0f);
  EXPECT_FLOAT_EQ(linear.sample(2.0f).x, 1.0f);
  for (const Track<1>* t : {&step, &linear, &cubic}) {
    EXPECT_FLOAT_EQ(t->sample(-5.0f).x, 0.0f) << "held before the first key";
    EXPECT_FLOAT_EQ(t->sample(9.0f).x, 0.0f) << "held after the last key";
    EXPECT_FLOAT_EQ(t->sample(1.0f).x, 2.0f) << "through every key";
  }
  // Catmull-Rom at the middle key: the neighbours' slope is 0, so the curve peaks there
  // and rises above the straight line before it.
  EXPECT_GT(cubic.sample(0.5f).x, 1.0f);
  EXPECT_LE(cubic.sample(1.05f).x, 2.0f);
  EXPECT_LE(cubic.sample(0.95f).x, 2.0f);
  // Evenly spaced keys on a line: the cubic is the line.
  const Track<1> ramp = track({0, 1, 2, 3}, {0, 1, 2, 3}, Interpolation::cubic);
  EXPECT_NEAR(ramp.sample(1.3f).x, 1.3f, 1e-5f);
}

TEST(Track, GivenTangentsMakeGltfsCubicSpline) {
  Track<1> t = track({0, 2}, {0, 0}, Interpolation::cubic);
  t.in_tangents = {glm::vec<1, float>(0.0f), glm::vec<1, float>(0.0f)};
  t.out_tangents = {glm::vec<1, float>(1.0f), glm::vec<1, float>(0.0f)};
  // Hermite with m0 = 1 per second over a 2 s span: at s = 0.5, (s^3 - 2s^2 + s) x 2 x 1.
  EXPECT_NEAR(t.sample(1.0f).x, 0.25f, 1e-6f);
}

// A scene whose camera orbits from +Z to +X, whose spot light rises while aiming at a
// fixed target, and whose block slides 2 m along X over 2 seconds.
std::filesystem::path write_animated_scene(const TempDir& dir) {
  const std::string block = testing::project_content("examples/assets/block.gltf").string();
  testing::write_text(dir / "shot.scene.json", R"({
    "version": 1,
    "models": [ { "name": "block", "file": ")" + block + R"(", "transform": { "translation": [0, 0.5, 0] },
                  "animation": { "translation": { "keys": [[0, [0, 0.5, 0]], [2, [2, 0.5, 0]]] } } } ],
    "lights": [ { "name": "spot", "type": "spot", "position": [0, 4, 0], "target": [0, 0, 0],
                  "inner_cone_deg": 20, "outer_cone_deg": 30,
                  "animation": { "position": { "keys": [[0, [0, 4, 0]], [2, [3, 4, 0]]], "interpolation": "cubic" } } } ],
    "cameras": [ { "position": [0, 1, 5], "target": [0, 0, 0], "vertical_fov_deg": 45, "near": 0.1, "far": 50,
                   "animation": { "position": { "keys": [[0, [0, 1, 5]], [1, [5, 1, 0]]], "interpolation": "step" },
                                  "vertical_fov_deg": { "keys": [[0, 45], [1, 30]] } } } ]
  })");
  return dir / "shot.scene.json";
}

TEST(SceneAnimation, ASceneFilesKeysPoseItsCameraLightAndModel) {
  TempDir dir;
  Scene scene = load_scene(write_animated_scene(dir));
  EXPECT_FLOAT_EQ(scene.animation.duration(), 2.0f);
  EXPECT_EQ(scene.animation.moving_meshes(), std::vector<std::size_t>{0});
  const Bounds rest = scene.meshes[0].bounds;
  EXPECT_GE(scene.bounds.max.x, rest.max.x + 2.0f - 1e-4f) << "the scene's bounds hold the block wherever it goes";

  scene.animation.pose(scene, 1.0f);
  EXPECT_EQ(scene.cameras[0].position, glm::vec3(5, 1, 0));  // step: the second key from t = 1 on
  EXPECT_NEAR(glm::degrees(scene.cameras[0].vertical_fov), 30.0f, 1e-4f);
  EXPECT_NEAR(scene.meshes[0].bounds.min.x, rest.min.x + 1.0f, 1e-5f);  // halfway along its slide
  EXPECT_NEAR(scene.meshes[0].bounds.max.y, rest.max.y, 1e-5f);
  const Light& spot = scene.lights[0];
  EXPECT_NEAR(spot.position.x, 1.5f, 1e-5f);  // the cubic's midpoint of two keys is the mean
  const glm::vec3 aim = glm::normalize(glm::vec3(0.0f) - spot.position);
  EXPECT_NEAR(glm::dot(spot.direction, aim), 1.0f, 1e-5f) << "it keeps aiming at its target";

  scene.animation.pose(scene, 0.0f);  // back to the start: posing depends on the time only
  EXPECT_EQ(scene.cameras[0].position, glm::vec3(0, 1, 5));
  EXPECT_NEAR(scene.meshes[0].bounds.min.x, rest.min.x, 1e-5f);
}

std::string error_of_scene(const TempDir& dir, const std::string& json) {
  testing::write_text(dir / "bad.scene.json", json);
  return testing::load_error_of([&] { load_scene(dir / "bad.scene.json"); });
}

TEST(SceneAnimationErrors, BadBlocksNameTheirPath) {
  TempDir dir;
  const std::string camera = R"("position": [0, 1, 5], "target": [0, 0, 0], "vertical_fov_deg": 45, "near": 0.1, "far": 50)";
  EXPECT_THAT(error_of_scene(dir, R"({"version": 1, "cameras": [{)" + camera +
                                      R"(, "animation": {"position": {"keys": [[1, [0,0,1]], [1, [0,0,2]]]}}}]})"),
              HasSubstr("cameras[0].animation.position.keys[1][0]: key times must increase"));
  EXPECT_THAT(error_of_scene(dir, R"({"version": 1, "cameras": [{)" + camera +
                                      R"(, "animation": {"position": {"keys": [[0, [0,0,1]]], "interpolation": "bezier"}}}]})"),
              HasSubstr("cameras[0].animation.position.interpolation: 'bezier' is not one of step, linear, cubic"));
  EXPECT_THAT(error_of_scene(dir, R"({"version": 1, "cameras": [{)" + camera + R"(, "animation": {"zoom": {"keys": [[0, 1]]}}}]})"),
              HasSubstr("cameras[0].animation.zoom"));
  EXPECT_THAT(error_of_scene(dir, R"({"version": 1, "cameras": [{)" + camera + R"(}], "lights": [{"type": "directional",
                                      "direction": [0, -1, 0], "animation": {"position": {"keys": [[0, [0, 1, 0]]]}}}]})"),
              HasSubstr("lights[0].animation.position: a directional light has no position"));
  EXPECT_THAT(error_of_scene(dir, R"({"version": 1, "cameras": [{)" + camera + R"(}], "models": [{"file": "x.gltf",
                                      "transform": {"matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1]},
                                      "animation": {"translation": {"keys": [[0, [0, 1, 0]]]}}}]})"),
              HasSubstr("models[0].transform: an animated model's transform must be translation / rotation_deg / scale"));
}

}  // namespace
}  // namespace animation_test
}  // namespace avsm::scene
