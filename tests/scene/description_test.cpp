// Scene files: what parses, and exact messages (file, JSON path, problem) for what does not.
#include "support.h"

#include "scene/description.h"

#include <glm/gtc/matrix_transform.hpp>

namespace avsm::scene {
namespace description_test {  // one per file: test targets are unity builds
namespace {

using testing::load_error_of;

const std::filesystem::path kSceneFile = "/scenes/test/scene.json";

SceneDescription parse(const std::string& text) { return parse_scene_description(text, kSceneFile); }

std::string error_of(const std::string& text) {
  return load_error_of([&] { parse(text); });
}

// A valid scene with one of everything; tests break one thing at a time.
std::string full_scene(const std::string& replace_from = "", const std::string& replace_to = "") {
  std::string text = R"({
  "version": 1,
  "description": "test",
  "models": [ { "name": "room", "file": "room.glb", "missing_normals": "smooth",
                "transform": { "translation": [1, 2, 3], "rotation_deg": [0, 90, 0], "scale": 2 } } ],
  "volumes": [ { "file": "/abs/smoke.vdb", "grid": "density", "extinction_scale": 4.5,
                 "albedo": [0.5, 0.6, 0.7], "majorant_brick_size": 16 } ],
  "hair": [ { "name": "pony", "file": "../hair/pony.tfx", "width": 0.001, "opacity": 0.4, "color": [0.3, 0.2, 0.1] },
            { "file": "curl.hair" } ],
  "lights": [
    { "name": "sun", "type": "directional", "direction": [0, -2, 0], "intensity": 2,
      "shadow": { "technique": "dsm", "nodes": 4, "resolution": 512, "filter": "point", "sort": false } },
    { "type": "spot", "position": [0, 5, 0], "target": [0, 0, 0], "inner_cone_deg": 20, "outer_cone_deg": 30,
      "color": [1, 0.5, 0.25],
      "shadow": { "technique": "avsm", "nodes": 16, "filter": "trilinear", "parameters": { "depth_bias": 0.002 } } }
  ],
  "cameras": [ { "name": "main", "position": [0, 1, 5], "target": [0, 1, 0], "vertical_fov_deg": 60, "near": 0.1, "far": 100 },
               { "position": [5, 1, 0], "target": [0, 1, 0], "up": [0, 2, 0], "vertical_fov_deg": 30, "near": 1, "far": 10 } ]
})";
  if (!replace_from.empty()) {
    const auto at = text.find(replace_from);
    EXPECT_NE(at, std::string::npos) << "test bug: '" << replace_from << "' not in the scene";
    if (at != std::string::npos) text.replace(at, replace_from.size(), replace_to);
  }
  return text;
}

TEST(SceneDescription, MinimalSceneNeedsOnlyVersionAndACamera) {
  const SceneDescription scene =
      parse(R"({"version": 1, "cameras": [{"position": [0,0,1], "target": [0,0,0], "vertical_fov_deg": 45, "near": 0.1, "far": 10}]})");
  EXPECT_TRUE(scene.models.empty() && scene.volumes.empty() && scene.hair.empty() && scene.lights.empty());
  ASSERT_EQ(scene.cameras.size(), 1u);
  EXPECT_EQ(scene.cameras[0].name, "camera0");
  EXPECT_EQ(scene.cameras[0].up, glm::vec3(0, 1, 0));
  EXPECT_FLOAT_EQ(scene.cameras[0].vertical_fov, glm::radians(45.0f));
}

TEST(SceneDescription, FullSceneParsesEveryField) {
  const SceneDescription scene = parse(full_scene());
  EXPECT_EQ(scene.description, "test");
  ASSERT_EQ(scene.models.size(), 1u);
  EXPECT_EQ(scene.models[0].file, "/scenes/test/room.glb");
  EXPECT_EQ(scene.models[0].missing_normals, NormalGeneration::smooth);
  // T * Rz * Ry * Rx * S: (1, 0, 0) -> scale 2 -> rotate 90 about Y -> (0, 0, -2) -> + (1, 2, 3).
  const glm::vec3 moved = glm::vec3(scene.models[0].transform * glm::vec4(1, 0, 0, 1));
  EXPECT_NEAR(moved.x, 1.0f, 1e-5f);
  EXPECT_NEAR(moved.y, 2.0f, 1e-5f);
  EXPECT_NEAR(moved.z, 1.0f, 1e-5f);

  ASSERT_EQ(scene.volumes.size(), 1u);
  EXPECT_EQ(scene.volumes[0].file, "/abs/smoke.vdb");
  EXPECT_EQ(scene.volumes[0].name, "smoke");
  EXPECT_FLOAT_EQ(scene.volumes[0].extinction_scale, 4.5f);
  EXPECT_EQ(scene.volumes[0].albedo, glm::vec3(0.5f, 0.6f, 0.7f));
  EXPECT_EQ(scene.volumes[0].majorant_brick_size, 16);

  ASSERT_EQ(scene.hair.size(), 2u);
  EXPECT_EQ(scene.hair[0].file, "/scenes/hair/pony.tfx");
  EXPECT_FLOAT_EQ(*scene.hair[0].width, 0.001f);
  EXPECT_FLOAT_EQ(*scene.hair[0].opacity, 0.4f);
  EXPECT_EQ(scene.hair[1].name, "curl");
  EXPECT_FALSE(scene.hair[1].width.has_value());

  ASSERT_EQ(scene.lights.size(), 2u);
  const Light& sun = scene.lights[0];
  EXPECT_EQ(sun.type, LightType::directional);
  EXPECT_EQ(sun.direction, glm::vec3(0, -1, 0));
  EXPECT_EQ(sun.shadow.technique, "dsm");
  EXPECT_EQ(sun.shadow.nodes, 4);
  EXPECT_EQ(sun.shadow.resolution, 512);
  EXPECT_EQ(sun.shadow.filter, ShadowFilter::point);
  EXPECT_FALSE(sun.shadow.sort);
  const Light& spot = scene.lights[1];
  EXPECT_EQ(spot.name, "light1");
  EXPECT_EQ(spot.type, LightType::spot);
  EXPECT_EQ(spot.direction, glm::vec3(0, -1, 0));  // from position to target
  EXPECT_FLOAT_EQ(spot.outer_cone_angle, glm::radians(30.0f));
  EXPECT_FLOAT_EQ(spot.inner_cone_angle, glm::radians(20.0f));
  EXPECT_EQ(spot.shadow.resolution, 1024);  // default
  EXPECT_EQ(spot.shadow.filter, ShadowFilter::trilinear);
  EXPECT_DOUBLE_EQ(spot.shadow.parameter("depth_bias", 0.0), 0.002);
  EXPECT_DOUBLE_EQ(spot.shadow.parameter("absent", 7.0), 7.0);
  EXPECT_EQ(spot.shadow.technique, "avsm");

  ASSERT_EQ(scene.cameras.size(), 2u);
  EXPECT_EQ(scene.cameras[1].up, glm::vec3(0, 1, 0));  // normalised
  EXPECT_FLOAT_EQ(scene.cameras[1].far_plane, 10.0f);
}

TEST(SceneDescription, MatrixTransformIsColumnMajor) {
  const SceneDescription scene = parse(full_scene(
      R"("translation": [1, 2, 3], "rotation_deg": [0, 90, 0], "scale": 2)",
      R"("matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 7,8,9,1])"));
  EXPECT_EQ(glm::vec3(scene.models[0].transform[3]), glm::vec3(7, 8, 9));
}

// ---- every error names the file and the JSON path ----

TEST(SceneDescriptionErrors, UnknownKeyNamesThePathAndSuggests) {
  EXPECT_THAT(error_of(full_scene(R"("nodes": 16)", R"("nodez": 16)")),
              StartsWith("/scenes/test/scene.json: lights[1].shadow.nodez: unknown key (did you mean 'nodes'?); allowed here: "
                         "technique, nodes, resolution, filter, kernel, kernel_radius, sort, build, fit, cascades, "
                         "clusters, layout, virtual_resolution, page_size, page_pool_mib, page_lod_bias, "
                         "page_volume_lod_bias, page_builds_per_frame, parameters, distance, cascade_blend"));
  EXPECT_THAT(error_of(full_scene(R"("version": 1,)", R"("version": 1, "colour": 2,)")),
              HasSubstr("scene.json: colour: unknown key"));
  EXPECT_THAT(error_of(full_scene(R"("grid": "density",)", R"("grid": "density", "density_scale": 2,)")),
              HasSubstr("volumes[0].density_scale: unknown key"));
}

TEST(SceneDescriptionErrors, MistypedValues) {
  EXPECT_THAT(error_of(full_scene(R"("intensity": 2)", R"("intensity": "bright")")),
              HasSubstr("scene.json: lights[0].intensity: expected a number, got a string"));
  EXPECT_THAT(error_of(full_scene(R"("nodes": 4)", R"("nodes": 8.0)")),
              HasSubstr("lights[0].shadow.nodes: expected a whole number, got a number with a fraction"));
  EXPECT_THAT(error_of(full_scene(R"("sort": false)", R"("sort": 0)")),
              HasSubstr("lights[0].shadow.sort: expected true or false, got an integer"));
  EXPECT_THAT(error_of(full_scene(R"("albedo": [0.5, 0.6, 0.7])", R"("albedo": [0.5, 0.6])")),
              HasSubstr("volumes[0].albedo: expected an array of 3 numbers, got an array of 2"));
  EXPECT_THAT(error_of(full_scene(R"("target": [0, 1, 0], "vertical_fov_deg": 60)", R"("target": [0, "1", 0], "vertical_fov_deg": 60)")),
              HasSubstr("cameras[0].target[1]: expected a number, got a string"));
  EXPECT_THAT(error_of(full_scene(R"("hair": [)", R"("hair": {"x": 1}, "unused": [)")),
              HasSubstr("hair: expected an array, got an object"));
  EXPECT_THAT(error_of(R"([1, 2])"), HasSubstr("scene.json: top level: expected an object, got an array"));
}

TEST(SceneDescriptionErrors, OutOfRangeValues) {
  EXPECT_THAT(error_of(full_scene(R"("nodes": 16)", R"("nodes": 10)")),
              HasSubstr("lights[1].shadow.nodes: must be 4, 8, 12 or 16, got 10"));
  // Which technique names exist is the renderer's registry's to say (tests/passes/technique_registry_test.cpp).
  EXPECT_THAT(error_of(full_scene(R"("technique": "dsm")", R"("technique": "")")),
              HasSubstr("lights[0].shadow.technique: must name a shadow technique"));
  EXPECT_THAT(error_of(full_scene(R"("filter": "point")", R"("filter": "cubic")")),
              HasSubstr("lights[0].shadow.filter: 'cubic' is not one of point, bilinear, trilinear"));
  EXPECT_THAT(error_of(full_scene(R"("resolution": 512)", R"("resolution": 8)")),
              HasSubstr("lights[0].shadow.resolution: must be 16 to 16384 texels, got 8"));
  EXPECT_THAT(error_of(full_scene(R"("outer_cone_deg": 30)", R"("outer_cone_deg": 95)")),
              HasSubstr("lights[1].outer_cone_deg: must be between 0 and 90 degrees"));
  EXPECT_THAT(error_of(full_scene(R"("inner_cone_deg": 20)", R"("inner_cone_deg": 40)")),
              HasSubstr("lights[1].inner_cone_deg: must be between 0 and outer_cone_deg"));
  EXPECT_THAT(error_of(full_scene(R"("near": 0.1, "far": 100)", R"("near": 0.1, "far": 0.05)")),
              HasSubstr("cameras[0].far: must be greater than near"));
  EXPECT_THAT(error_of(full_scene(R"("up": [0, 2, 0])", R"("up": [-1, 0, 0])")),
              HasSubstr("cameras[1].up: is zero or parallel to the viewing direction"));
  EXPECT_THAT(error_of(full_scene(R"("extinction_scale": 4.5)", R"("extinction_scale": -1)")),
              HasSubstr("volumes[0].extinction_scale: must be >= 0"));
  EXPECT_THAT(error_of(full_scene(R"("albedo": [0.5, 0.6, 0.7])", R"("albedo": [0.5, 1.6, 0.7])")),
              HasSubstr("volumes[0].albedo: each component must be in [0, 1]"));
  EXPECT_THAT(error_of(full_scene(R"("opacity": 0.4)", R"("opacity": 1.4)")), HasSubstr("hair[0].opacity: must be in [0, 1]"));
  EXPECT_THAT(error_of(full_scene(R"("direction": [0, -2, 0])", R"("direction": [0, 0, 0])")),
              HasSubstr("lights[0].direction: gives no direction (zero length)"));
  EXPECT_THAT(error_of(full_scene(R"("majorant_brick_size": 16)", R"("majorant_brick_size": 100)")),
              HasSubstr("volumes[0].majorant_brick_size: must be 2 to 64 voxels"));
  EXPECT_THAT(error_of(full_scene(R"("scale": 2)", R"("scale": [1, 0, 1])")),
              HasSubstr("models[0].transform: transform is singular"));
  EXPECT_THAT(error_of(full_scene(R"("depth_bias": 0.002)", R"("depth_bias": "small")")),
              HasSubstr("lights[1].shadow.parameters.depth_bias: expected a number, got a string"));
}

TEST(SceneDescription, VolumeShadingAndLightingCache) {
  const SceneDescription defaults = parse(full_scene());
  EXPECT_EQ(defaults.volume_shading.mode, VolumeShading::Mode::fast);
  EXPECT_EQ(defaults.volume_shading.resolution_divisor, 2);
  EXPECT_FLOAT_EQ(defaults.volume_shading.step_voxels, 2.0f);
  EXPECT_FLOAT_EQ(defaults.volumes[0].lighting_cache_downsample, 2.0f);

  const SceneDescription scene = parse(full_scene(
      R"("majorant_brick_size": 16 } ],)",
      R"("majorant_brick_size": 16, "lighting_cache": { "downsample": 4 } } ],)"
      R"( "volume_shading": { "mode": "reference", "resolution_divisor": 4, "step_voxels": 0.5 },)"));
  EXPECT_FLOAT_EQ(scene.volumes[0].lighting_cache_downsample, 4.0f);
  EXPECT_EQ(scene.volume_shading.mode, VolumeShading::Mode::reference);
  EXPECT_EQ(scene.volume_shading.resolution_divisor, 4);
  EXPECT_FLOAT_EQ(scene.volume_shading.step_voxels, 0.5f);
}

TEST(SceneDescriptionErrors, VolumeShadingAndLightingCacheOutOfRange) {
  auto with_cache = [](const std::string& cache) {
    return full_scene(R"("majorant_brick_size": 16 })", R"("majorant_brick_size": 16, "lighting_cache": )" + cache + " }");
  };
  EXPECT_THAT(error_of(with_cache(R"({ "downsample": 0.5 })")),
              HasSubstr("volumes[0].lighting_cache.downsample: must be 1 to 8 voxels per cache cell"));
  EXPECT_THAT(error_of(with_cache(R"("none")")),
              HasSubstr("volumes[0].lighting_cache: must be \"off\" or an object with \"downsample\""));
  EXPECT_FALSE(parse(with_cache(R"("off")")).volumes[0].lighting_cache);
  EXPECT_THAT(error_of(with_cache(R"({ "downsampel": 2 })")),
              HasSubstr("volumes[0].lighting_cache.downsampel: unknown key (did you mean 'downsample'?)"));
  auto with_shading = [](const std::string& shading) {
    return full_scene(R"("majorant_brick_size": 16 } ],)",
                      R"("majorant_brick_size": 16 } ], "volume_shading": )" + shading + " },");
  };
  EXPECT_THAT(error_of(with_shading(R"({ "mode": "slow")")),
              HasSubstr("volume_shading.mode: 'slow' is not one of fast, reference, hidden"));
  EXPECT_THAT(error_of(with_shading(R"({ "resolution_divisor": 3)")),
              HasSubstr("volume_shading.resolution_divisor: must be 1, 2 or 4, got 3"));
  EXPECT_THAT(error_of(with_shading(R"({ "step_voxels": 10)")),
              HasSubstr("volume_shading.step_voxels: must be 0.125 to 4 voxels"));
}

TEST(SceneDescription, VolumeMultipleScatteringAndSkyLight) {
  const SceneDescription defaults = parse(full_scene());
  EXPECT_EQ(defaults.volumes[0].multiple_scattering, MultipleScattering{});
  EXPECT_GT(defaults.volumes[0].multiple_scattering.octaves, 1) << "on by default";
  EXPECT_FLOAT_EQ(defaults.volumes[0].sky_light, 1.0f);
  auto with = [](const std::string& keys) {
    return full_scene(R"("majorant_brick_size": 16 })", R"("majorant_brick_size": 16, )" + keys + " }");
  };
  const SceneDescription scene =
      parse(with(R"("multiple_scattering": { "octaves": 6, "attenuation": 0.25, "contribution": 0.5 }, "sky_light": 2)"));
  EXPECT_EQ(scene.volumes[0].multiple_scattering, (MultipleScattering{6, 0.25f, 0.5f}));
  EXPECT_FLOAT_EQ(scene.volumes[0].sky_light, 2.0f);
  EXPECT_EQ(parse(with(R"("multiple_scattering": "off")")).volumes[0].multiple_scattering.octaves, 1);
  EXPECT_FLOAT_EQ(parse(with(R"("sky_light": 0)")).volumes[0].sky_light, 0.0f);
}

TEST(SceneDescriptionErrors, VolumeMultipleScatteringAndSkyLightOutOfRange) {
  auto with = [](const std::string& keys) {
    return full_scene(R"("majorant_brick_size": 16 })", R"("majorant_brick_size": 16, )" + keys + " }");
  };
  EXPECT_THAT(error_of(with(R"("multiple_scattering": { "octaves": 9 })")),
              HasSubstr("volumes[0].multiple_scattering.octaves: must be 1 (single scattering) to 8"));
  EXPECT_THAT(error_of(with(R"("multiple_scattering": { "attenuation": 0 })")),
              HasSubstr("volumes[0].multiple_scattering.attenuation: must be in (0, 1]"));
  EXPECT_THAT(error_of(with(R"("multiple_scattering": { "contribution": 1.5 })")),
              HasSubstr("volumes[0].multiple_scattering.contribution: must be in [0, 1]"));
  EXPECT_THAT(error_of(with(R"("multiple_scattering": "on")")),
              HasSubstr("volumes[0].multiple_scattering: must be \"off\" or an object with \"octaves\""));
  EXPECT_THAT(error_of(with(R"("multiple_scattering": { "octave": 2 })")),
              HasSubstr("volumes[0].multiple_scattering.octave: unknown key (did you mean 'octaves'?)"));
  EXPECT_THAT(error_of(with(R"("sky_light": -1)")), HasSubstr("volumes[0].sky_light: must be 0 (no sky light) to 4"));
}

// A rect light added to the scene's lights: `keys` after its type.
std::string with_rect(const std::string& keys) {
  return full_scene(R"("lights": [)", R"("lights": [ { "name": "softbox", "type": "rect", )" + keys + " },");
}

TEST(SceneDescription, RectLight) {
  const SceneDescription scene = parse(with_rect(
      R"("position": [0, 3, 0], "target": [0, 0, 0], "size": [2, 0.5], "two_sided": true, "virtual_lights": 32,
         "color": [1, 0.9, 0.8], "intensity": 4, "range": 10, "shadow": { "resolution": 128 })"));
  const Light& light = scene.lights.at(0);
  EXPECT_EQ(light.type, LightType::rect);
  EXPECT_EQ(light.position, glm::vec3(0.0f, 3.0f, 0.0f));
  EXPECT_EQ(light.direction, glm::vec3(0.0f, -1.0f, 0.0f));
  EXPECT_EQ(light.size, glm::vec2(2.0f, 0.5f));
  EXPECT_TRUE(light.two_sided);
  EXPECT_EQ(light.virtual_lights, 32);
  EXPECT_FLOAT_EQ(light.range, 10.0f);
  EXPECT_EQ(light.shadow.resolution, 128);
  const Light defaults = parse(with_rect(R"("position": [0, 3, 0], "direction": [0, -1, 0], "size": [1, 1])")).lights[0];
  EXPECT_FALSE(defaults.two_sided);
  EXPECT_EQ(defaults.virtual_lights, 64);
}

TEST(SceneDescription, DiskAndSphereLights) {
  const SceneDescription scene = parse(full_scene(R"("lights": [)", R"("lights": [
      { "name": "disk", "type": "disk", "position": [0, 3, 0], "direction": [0, -1, 0], "radius": 0.4, "two_sided": true },
      { "name": "bulb", "type": "sphere", "position": [1, 2, 0], "radius": 0.1, "virtual_lights": 8 },)"));
  EXPECT_EQ(scene.lights.at(0).type, LightType::disk);
  EXPECT_FLOAT_EQ(scene.lights[0].radius, 0.4f);
  EXPECT_TRUE(scene.lights[0].two_sided);
  EXPECT_EQ(scene.lights.at(1).type, LightType::sphere);
  EXPECT_FLOAT_EQ(scene.lights[1].radius, 0.1f);
  EXPECT_EQ(scene.lights[1].virtual_lights, 8);
}

TEST(SceneDescriptionErrors, RectLight) {
  EXPECT_THAT(error_of(with_rect(R"("position": [0, 3, 0], "direction": [0, -1, 0])")),
              HasSubstr("lights[0].size: required key is missing"));
  EXPECT_THAT(error_of(with_rect(R"("position": [0, 3, 0], "direction": [0, -1, 0], "size": [1, 0])")),
              HasSubstr("lights[0].size: width and height must be > 0"));
  EXPECT_THAT(error_of(with_rect(R"("position": [0, 3, 0], "direction": [0, -1, 0], "size": [1])")),
              HasSubstr("lights[0].size: expected [width, height]"));
  EXPECT_THAT(error_of(with_rect(R"("position": [0, 3, 0], "size": [1, 1])")),
              HasSubstr("lights[0].direction: give exactly one of 'direction' and 'target'"));
  EXPECT_THAT(error_of(with_rect(R"("position": [0, 3, 0], "direction": [0, -1, 0], "size": [1, 1], "virtual_lights": 0)")),
              HasSubstr("lights[0].virtual_lights: must be 1 to 256"));
  EXPECT_THAT(error_of(with_rect(R"("position": [0, 3, 0], "direction": [0, -1, 0], "size": [1, 1], "shadow": {"virtual_lights": 4})")),
              HasSubstr("lights[0].shadow.virtual_lights: unknown key"));
  EXPECT_THAT(error_of(with_rect(R"("position": [0, 3, 0], "direction": [0, -1, 0], "size": [1, 1], "outer_cone_deg": 30)")),
              HasSubstr("lights[0].outer_cone_deg: only spot lights have this"));
  EXPECT_THAT(error_of(full_scene(R"("intensity": 2,)", R"("intensity": 2, "size": [1, 1],)")),
              HasSubstr("lights[0].size: only rect lights have this"));
  auto with_light = [](const std::string& light) {
    return full_scene(R"("lights": [)", R"("lights": [ )" + light + ",");
  };
  EXPECT_THAT(error_of(with_light(R"({ "type": "disk", "position": [0, 3, 0], "direction": [0, -1, 0] })")),
              HasSubstr("lights[0].radius: required key is missing"));
  EXPECT_THAT(error_of(with_light(R"({ "type": "sphere", "position": [0, 3, 0], "radius": 0 })")),
              HasSubstr("lights[0].radius: must be > 0"));
  EXPECT_THAT(error_of(with_light(R"({ "type": "sphere", "position": [0, 3, 0], "radius": 1, "direction": [0, -1, 0] })")),
              HasSubstr("lights[0].direction: sphere lights shine every way; remove it"));
  EXPECT_THAT(error_of(with_light(R"({ "type": "sphere", "position": [0, 3, 0], "radius": 1, "two_sided": true })")),
              HasSubstr("lights[0].two_sided: only rect and disk lights have this"));
}

// The fog block (scene/fog.h): a global medium, boxes of their own, the sky and the grid.
std::string with_fog(const std::string& fog) { return full_scene(R"("version": 1,)", R"("version": 1, "fog": )" + fog + ","); }

TEST(SceneDescription, Fog) {
  const SceneDescription none = parse(full_scene());
  EXPECT_FALSE(none.fog.enabled()) << "no fog unless the file has one";
  const SceneDescription scene = parse(with_fog(R"({ "scattering": 0.1, "absorption": 0.02, "color": [1, 0.9, 0.8],
      "phase_g": 0.6, "sky_light": 0.5, "froxel_pixels": 8, "slices": 32, "distance": 20,
      "boxes": [ { "min": [-1, 0, -1], "max": [1, 0.5, 1], "scattering": 0.4, "phase_g": -0.2 } ] })"));
  const Fog& fog = scene.fog;
  EXPECT_TRUE(fog.enabled());
  EXPECT_FLOAT_EQ(fog.global.scattering, 0.1f);
  EXPECT_FLOAT_EQ(fog.global.absorption, 0.02f);
  EXPECT_EQ(fog.global.color, glm::vec3(1.0f, 0.9f, 0.8f));
  EXPECT_FLOAT_EQ(fog.global.phase_g, 0.6f);
  EXPECT_FLOAT_EQ(fog.sky_light, 0.5f);
  EXPECT_EQ(fog.grid.froxel_pixels, 8);
  EXPECT_EQ(fog.grid.slices, 32);
  EXPECT_FLOAT_EQ(fog.grid.distance, 20.0f);
  ASSERT_EQ(fog.boxes.size(), 1u);
  EXPECT_EQ(fog.boxes[0].bounds.min, glm::vec3(-1.0f, 0.0f, -1.0f));
  EXPECT_EQ(fog.boxes[0].bounds.max, glm::vec3(1.0f, 0.5f, 1.0f));
  EXPECT_FLOAT_EQ(fog.boxes[0].medium.scattering, 0.4f);
  EXPECT_FLOAT_EQ(fog.boxes[0].medium.absorption, 0.0f) << "a box's medium starts empty, not as the global one";
  EXPECT_FLOAT_EQ(fog.boxes[0].medium.phase_g, -0.2f);
  EXPECT_TRUE(parse(with_fog(R"({ "boxes": [ { "min": [0, 0, 0], "max": [1, 1, 1], "absorption": 1 } ] })")).fog.enabled())
      << "a box alone is fog";
}

TEST(SceneDescriptionErrors, FogOutOfRange) {
  EXPECT_THAT(error_of(with_fog(R"({ "scattering": -1 })")), HasSubstr("fog.scattering: must be 0 to 100 per metre"));
  EXPECT_THAT(error_of(with_fog(R"({ "absorption": 200 })")), HasSubstr("fog.absorption: must be 0 to 100 per metre"));
  EXPECT_THAT(error_of(with_fog(R"({ "phase_g": 1 })")), HasSubstr("fog.phase_g: must be -0.95 to 0.95"));
  EXPECT_THAT(error_of(with_fog(R"({ "color": [2, 1, 1] })")), HasSubstr("fog.color: each component must be in [0, 1]"));
  EXPECT_THAT(error_of(with_fog(R"({ "sky_light": 5 })")), HasSubstr("fog.sky_light: must be 0 (no sky light) to 4"));
  EXPECT_THAT(error_of(with_fog(R"({ "froxel_pixels": 2 })")), HasSubstr("fog.froxel_pixels: must be 4 to 64 pixels"));
  EXPECT_THAT(error_of(with_fog(R"({ "slices": 300 })")), HasSubstr("fog.slices: must be 8 to 256 depth slices"));
  EXPECT_THAT(error_of(with_fog(R"({ "distance": -2 })")), HasSubstr("fog.distance: must be >= 0 metres"));
  EXPECT_THAT(error_of(with_fog(R"({ "density": 1 })")), HasSubstr("fog.density: unknown key"));
  EXPECT_THAT(error_of(with_fog(R"({ "boxes": {} })")), HasSubstr("fog.boxes: expected an array of boxes"));
  EXPECT_THAT(error_of(with_fog(R"({ "boxes": [ { "min": [0, 0, 0], "max": [1, 0, 1] } ] })")),
              HasSubstr("fog.boxes[0].max: must be greater than min on every axis"));
  EXPECT_THAT(error_of(with_fog(R"({ "boxes": [ { "max": [1, 1, 1] } ] })")),
              HasSubstr("fog.boxes[0].min: required key is missing"));
  EXPECT_THAT(error_of(with_fog(R"({ "boxes": [ { "min": [0, 0, 0], "max": [1, 1, 1], "phase_g": -1 } ] })")),
              HasSubstr("fog.boxes[0].phase_g: must be -0.95 to 0.95"));
}

TEST(SceneDescriptionErrors, MissingAndContradictoryKeys) {
  EXPECT_THAT(error_of(full_scene(R"("version": 1,)", "")), HasSubstr("scene.json: version: required key is missing"));
  EXPECT_THAT(error_of(full_scene(R"("version": 1,)", R"("version": 2,)")), HasSubstr("version: unsupported version 2"));
  EXPECT_THAT(error_of(R"({"version": 1})"), HasSubstr("cameras: a scene needs at least one camera"));
  EXPECT_THAT(error_of(R"({"version": 1, "cameras": []})"), HasSubstr("cameras: a scene needs at least one camera"));
  EXPECT_THAT(error_of(full_scene(R"("grid": "density",)", "")), HasSubstr("volumes[0].grid: required key is missing"));
  EXPECT_THAT(error_of(full_scene(R"("type": "spot", )", "")), HasSubstr("lights[1].type: required key is missing"));
  EXPECT_THAT(error_of(full_scene(R"("intensity": 2,)", R"("intensity": 2, "position": [1, 1, 1],)")),
              HasSubstr("lights[0].position: only spot, point and area lights have this"));
  EXPECT_THAT(error_of(full_scene(R"("target": [0, 0, 0], "inner)", R"("target": [0, 0, 0], "direction": [0, -1, 0], "inner)")),
              HasSubstr("lights[1].direction: give exactly one of 'direction' and 'target'"));
  EXPECT_THAT(error_of(full_scene(R"("scale": 2 })", R"("scale": 2, "matrix": [1,0,0,0, 0,1,0,0, 0,0,1,0, 0,0,0,1] })")),
              HasSubstr("models[0].transform.translation: cannot be combined with 'matrix'"));
  EXPECT_THAT(error_of(full_scene(R"("translation": [1, 2, 3], "rotation_deg": [0, 90, 0], "scale": 2)",
                                  R"("matrix": [1,0,0,1, 0,1,0,0, 0,0,1,0, 0,0,0,1])")),
              HasSubstr("models[0].transform.matrix: not an affine transform"));
  EXPECT_THAT(error_of(full_scene(R"({ "position": [5, 1, 0])", R"({ "name": "main", "position": [5, 1, 0])")),
              HasSubstr("cameras[1].name: 'main' is already used by cameras[0]; names must be unique"));
}

TEST(SceneDescriptionErrors, HairFilesNeedAKnownFormatAndWidthsWhereTheFileHasNone) {
  EXPECT_THAT(error_of(full_scene(R"("width": 0.001, )", "")),
              HasSubstr("hair[0].width: required for .tfx files, which store no absolute strand widths"));
  EXPECT_THAT(error_of(full_scene(R"("curl.hair")", R"("curl.obj")")),
              HasSubstr("hair[1].file: unknown hair format '.obj' (expected .tfx, .hair, .gltf or .glb)"));
  EXPECT_THAT(error_of(full_scene(R"("curl.hair")", R"("")")), HasSubstr("hair[1].file: must not be empty"));
}

TEST(SceneDescriptionErrors, InvalidJsonAndDuplicateKeys) {
  EXPECT_THAT(error_of("{\n  \"version\": 1,\n  \"cameras\": [,]\n}"),
              AllOf(HasSubstr("scene.json: invalid JSON: parse error at line 3, column 15"), ::testing::Not(HasSubstr("json.exception"))));
  EXPECT_THAT(error_of(full_scene(R"("intensity": 2,)", R"("intensity": 2, "intensity": 3,)")),
              HasSubstr("scene.json: lights[0].intensity: duplicate key"));
  EXPECT_THAT(error_of(full_scene(R"("depth_bias": 0.002)", R"("depth_bias": 0.002, "depth_bias": 0.003)")),
              HasSubstr("lights[1].shadow.parameters.depth_bias: duplicate key"));
  EXPECT_THAT(error_of(""), HasSubstr("invalid JSON"));
  // Found by the fuzzer: nlohmann reports number overflow as out_of_range, not parse_error.
  EXPECT_THAT(error_of(R"({"version": 1e999})"), HasSubstr("scene.json: invalid JSON: number overflow parsing '1e999'"));
}

TEST(SceneDescriptionErrors, MissingSceneFile) {
  EXPECT_THAT(load_error_of([] { read_scene_description("/nonexistent/scene.json"); }),
              HasSubstr("/nonexistent/scene.json: file not found"));
}

TEST(SceneDescription, EveryExampleSceneParses) {
  const auto examples = testing::project_content("examples");
  AVSM_REQUIRE_FILE(examples);
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(examples)) {
    if (entry.path().extension() != ".json") continue;
    EXPECT_NO_THROW(read_scene_description(entry.path())) << entry.path();
    ++count;
  }
  EXPECT_GE(count, 6);
  EXPECT_NO_THROW(read_scene_description(testing::project_content("real_assets.scene.json")));
}

}  // namespace
}  // namespace description_test
}  // namespace avsm::scene
