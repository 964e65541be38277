// Whole scenes: the generated default scene, the real-asset scene, the
// documented examples, and how asset errors are reported.
#include "support.h"

#include "scene/scene.h"

#include <algorithm>
#include <limits>

namespace avsm::scene {
namespace scene_test {  // one per file: test targets are unity builds
namespace {

using testing::TempDir;
using testing::load_error_of;

bool inside(const Bounds& outer, const Bounds& inner, float slack) {
  return glm::all(glm::lessThanEqual(outer.min - slack, inner.min)) &&
         glm::all(glm::lessThanEqual(inner.max, outer.max + slack));
}

TEST(Scene, DefaultSceneLoadsWithEveryKindOfContent) {
  const auto file = testing::default_content("scene.json");
  ASSERT_TRUE(std::filesystem::exists(file)) << file << " is written by the build (target avsm_default_content)";
  const Scene scene = load_scene(file);
  EXPECT_TRUE(scene.warnings.empty()) << scene.warnings.front();

  // Stage: floor, box, sphere, rod and two posts; the cylinder material is shared.
  EXPECT_EQ(scene.meshes.size(), 6u);
  EXPECT_EQ(scene.materials.size(), 4u);
  for (const Mesh& mesh : scene.meshes) EXPECT_EQ(scene.materials[mesh.material].alpha_mode, AlphaMode::opaque);

  ASSERT_EQ(scene.volumes.size(), 1u);
  const Volume& plume = scene.volumes[0];
  EXPECT_EQ(plume.name, "plume");
  EXPECT_GT(plume.stats.active_voxel_count, 100000u);
  EXPECT_GT(plume.stats.max, 1.0f);
  EXPECT_FLOAT_EQ(plume.extinction_scale, 1.5f);
  const glm::ivec3 extent = plume.active_index_max - plume.active_index_min + 1;
  EXPECT_GE(glm::min(extent.x, extent.z), 64);  // "64 to 96 voxels across"
  EXPECT_LE(glm::max(extent.x, extent.z), 96);
  EXPECT_NEAR(plume.world_bounds.min.y, -0.025f, 0.03f);  // stands on the floor
  // Dense enough to shadow, thin enough to see through: partial transmittance
  // across the column, more at the top.
  const float across_middle = transmittance(plume, {-3.3f, 1.5f, -0.4f}, {0.7f, 1.5f, -0.4f});
  const float across_top = transmittance(plume, {-3.3f, 2.9f, -0.4f}, {0.7f, 2.9f, -0.4f});
  EXPECT_GT(across_middle, 0.05f);
  EXPECT_LT(across_middle, 0.6f);
  EXPECT_GT(across_top, across_middle);
  std::vector<std::string> names;
  for (const Mesh& mesh : scene.meshes) names.push_back(mesh.name);
  EXPECT_EQ(names, (std::vector<std::string>{"stage/floor", "stage/box", "stage/sphere", "stage/rod", "stage/post_left",
                                              "stage/post_right"}));

  ASSERT_EQ(scene.hair.size(), 1u);
  const HairGroom& curtain = scene.hair[0];
  EXPECT_EQ(curtain.strand_count(), 2700u);
  EXPECT_EQ(curtain.width_kind, StrandWidth::absolute);
  EXPECT_NEAR(curtain.strand_width[0], 0.00075f, 0.00016f);  // metres, from the file
  EXPECT_NEAR(curtain.bounds.max.y, 1.9f - 0.0125f, 0.01f);  // roots under the rod
  EXPECT_NEAR(curtain.bounds.center().x, 1.0f, 0.05f);

  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].type, LightType::directional);
  EXPECT_EQ(scene.lights[1].type, LightType::spot);
  // The frame the project's targets are measured on: 256^2 AVSM-8 for both lights.
  for (const Light& light : scene.lights) {
    EXPECT_EQ(light.shadow.nodes, 8);
    EXPECT_EQ(light.shadow.resolution, 256);
  }
  EXPECT_EQ(scene.lights[1].shadow.filter, ShadowFilter::trilinear);
  ASSERT_EQ(scene.cameras.size(), 1u);
  EXPECT_TRUE(inside(Bounds{glm::vec3(-4.1f, -0.1f, -4.1f), glm::vec3(4.1f, 3.5f, 4.1f)}, scene.bounds, 0.0f));
}

// bench/avsm/lights.py's scenes: the sparse one's caster groups lie far apart over a
// ground much larger than them; the many-lights one's every first 4k lights hold the
// same mix of types (so that N lights measure N times the cost of one).
TEST(Scene, SparseBenchSceneSpreadsItsCastersOverALargeGround) {
  const Scene scene = load_scene(testing::default_content("bench_sparse.scene.json"));
  ASSERT_EQ(scene.volumes.size(), 2u);
  ASSERT_EQ(scene.hair.size(), 1u);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_EQ(scene.lights[0].type, LightType::directional);
  EXPECT_GT(glm::min(scene.bounds.size().x, scene.bounds.size().z), 90.0f);
  const std::vector<Bounds> groups = {scene.volumes[0].world_bounds, scene.volumes[1].world_bounds,
                                      scene.hair[0].bounds};
  for (size_t a = 0; a < groups.size(); ++a)
    for (size_t b = a + 1; b < groups.size(); ++b) {
      const glm::vec3 apart = groups[a].center() - groups[b].center();
      EXPECT_GT(glm::length(glm::vec2(apart.x, apart.z)), 19.0f) << "caster groups " << a << " and " << b;
    }
}

TEST(Scene, ManyLightsBenchSceneMixesLightTypesEvenly) {
  const Scene scene = load_scene(testing::default_content("bench_many_lights.scene.json"));
  ASSERT_EQ(scene.lights.size(), 16u);
  for (size_t first = 0; first < 16; first += 4) {
    int directional = 0, spot = 0, point = 0;
    for (size_t i = first; i < first + 4; ++i) {
      const Light& light = scene.lights[i];
      directional += light.type == LightType::directional;
      spot += light.type == LightType::spot;
      point += light.type == LightType::point;
      EXPECT_EQ(light.shadow.resolution, 256) << light.name;
    }
    EXPECT_EQ(directional, 1) << "lights " << first << " to " << first + 3;
    EXPECT_EQ(spot, 2) << "lights " << first << " to " << first + 3;
    EXPECT_EQ(point, 1) << "lights " << first << " to " << first + 3;
  }
}

TEST(Scene, RealAssetsSitTogetherInsideTheCornellBox) {
  for (const char* asset : {"smoke1/smoke.vdb", "ponytail/ponytail_all.hair", "cornell_box/CornellBox.glb"})
    AVSM_REQUIRE_FILE(testing::shared_content(asset));
  const Scene scene = load_scene(testing::project_content("real_assets.scene.json"));
  ASSERT_EQ(scene.volumes.size(), 1u);
  EXPECT_EQ(scene.volumes[0].stats.active_voxel_count, 1049275u);
  ASSERT_EQ(scene.hair.size(), 1u);
  EXPECT_EQ(scene.hair[0].strand_count(), 4714u);
  EXPECT_EQ(scene.meshes.size(), 6u);
  Bounds room;
  for (const Mesh& mesh : scene.meshes) room.extend(mesh.bounds);
  EXPECT_NEAR(room.size().y, 5.49f, 0.05f);  // metres
  EXPECT_TRUE(inside(room, scene.volumes[0].world_bounds, 0.0f));
  EXPECT_TRUE(inside(room, scene.hair[0].bounds, 0.0f));
  EXPECT_GT(scene.volumes[0].world_bounds.min.y, room.min.y - 0.05f);
  EXPECT_EQ(scene.lights.size(), 2u);
  // Cameras stand outside the open front of the box and look into it.
  for (const Camera& camera : scene.cameras) EXPECT_TRUE(room.contains(camera.target)) << camera.name;
}

const HairGroom& groom_named(const Scene& scene, const std::string& name) {
  for (const HairGroom& groom : scene.hair)
    if (groom.name == name) return groom;
  throw std::runtime_error("no groom named " + name);
}

TEST(Scene, HairFormatsExampleHasSintelsHairOnHerHeadAndPonytailsBeside) {
  for (const char* asset : {"sintel/sintel_hair.tfx", "sintel/sintel_head.glb", "ponytail/back.tfx",
                            "ponytail/ponytail_all.hair"})
    AVSM_REQUIRE_FILE(testing::shared_content(asset));
  const Scene scene = load_scene(testing::project_content("examples/hair_formats.scene.json"));
  const auto head = std::find_if(scene.meshes.begin(), scene.meshes.end(),
                                 [](const Mesh& mesh) { return mesh.name.starts_with("sintel_head/"); });
  ASSERT_NE(head, scene.meshes.end());
  const HairGroom& sintel = groom_named(scene, "sintel");
  ASSERT_EQ(sintel.strand_count(), 228u);
  // Every root sits on the scalp: within 3 cm of a head vertex (the farthest is
  // 2.3 units in the files' own units, before the scene's scale of 0.01).
  float farthest_root = 0.0f;
  for (std::size_t s = 0; s < sintel.strand_count(); ++s) {
    const glm::vec3 root = sintel.points[sintel.strand_offsets[s]];
    float nearest = std::numeric_limits<float>::infinity();
    for (const glm::vec3& vertex : head->positions) nearest = std::min(nearest, glm::distance(root, vertex));
    farthest_root = std::max(farthest_root, nearest);
  }
  EXPECT_LT(farthest_root, 0.03f);
  EXPECT_GT(sintel.bounds.max.y, head->bounds.max.y);  // the hair covers the crown
  // The TressFX 3 parts to the left, the cyHair ponytail to the right, clear of the head.
  for (const char* part : {"tfx3_back", "tfx3_front_top", "tfx3_side", "tfx3_tail"})
    EXPECT_LT(groom_named(scene, part).bounds.max.x, head->bounds.min.x) << part;
  EXPECT_GT(groom_named(scene, "cyhair_ponytail").bounds.min.x, head->bounds.max.x);
  for (const HairGroom& groom : scene.hair) EXPECT_GT(groom.bounds.min.y, -0.001f) << groom.name << " is below the floor";
}

TEST(Scene, EveryExampleSceneLoads) {
  const auto examples = testing::project_content("examples");
  AVSM_REQUIRE_FILE(examples);
  AVSM_REQUIRE_FILE(testing::shared_content("README.md"));
  int count = 0;
  for (const auto& entry : std::filesystem::directory_iterator(examples)) {
    if (entry.path().extension() != ".json") continue;
    try {
      const Scene scene = load_scene(entry.path());
      EXPECT_FALSE(scene.bounds.empty()) << entry.path();
    } catch (const LoadError& error) {
      ADD_FAILURE() << error.what();
    }
    ++count;
  }
  EXPECT_GE(count, 6);
}

TEST(Scene, HairWidthsBecomeWorldUnits) {
  const auto pony = testing::shared_content("ponytail/ponytail_all.hair");
  const auto tail = testing::shared_content("ponytail/tail.tfx");
  AVSM_REQUIRE_FILE(pony);
  AVSM_REQUIRE_FILE(tail);
  SceneDescription description;
  description.file = "in-memory.json";
  description.cameras.push_back(Camera{});
  HairEntry from_file{"pony", pony};
  from_file.transform = glm::mat4(glm::vec4(0.01f, 0, 0, 0), glm::vec4(0, 0.01f, 0, 0), glm::vec4(0, 0, 0.01f, 0), glm::vec4(0, 0, 0, 1));
  HairEntry overridden{"tail", tail};
  overridden.width = 0.0002f;
  overridden.opacity = 0.3f;
  overridden.color = glm::vec3(0.5f, 0.4f, 0.3f);
  description.hair = {from_file, overridden};
  const Scene scene = load_scene(description);
  EXPECT_FLOAT_EQ(scene.hair[0].strand_width[0], 0.01f);  // thickness 1.0 x scale 0.01
  EXPECT_NEAR(scene.hair[0].bounds.size().y, 1.268f, 0.01f);
  EXPECT_FLOAT_EQ(scene.hair[1].strand_width[17], 0.0002f);
  EXPECT_FLOAT_EQ(scene.hair[1].strand_opacity[17], 0.3f);
  EXPECT_EQ(scene.hair[1].strand_color[17], glm::vec3(0.5f, 0.4f, 0.3f));
  EXPECT_EQ(scene.hair[1].name, "tail");
}

TEST(Scene, GltfLinesAreHairOnlyWhenListedAsHair) {
  const auto lines = testing::assimp_model("glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_03.gltf");
  AVSM_REQUIRE_FILE(lines);
  TempDir dir;
  const std::string camera = R"("cameras": [{"position": [0,0,3], "target": [0,0,0], "vertical_fov_deg": 45, "near": 0.1, "far": 10}])";
  testing::write_text(dir / "scene.json", R"({"version": 1, "models": [{"file": ")" + lines.string() + R"("}],
    "hair": [{"file": ")" + lines.string() + R"(", "width": 0.01, "transform": {"translation": [0, 5, 0]}}], )" + camera + "}");
  const Scene scene = load_scene(dir / "scene.json");
  EXPECT_TRUE(scene.meshes.empty());
  ASSERT_EQ(scene.warnings.size(), 1u);
  EXPECT_THAT(scene.warnings[0], HasSubstr("models[0] (Mesh_PrimitiveMode_03.gltf): 1 line strands ignored"));
  ASSERT_EQ(scene.hair.size(), 1u);
  EXPECT_EQ(scene.hair[0].points.size(), 5u);
  EXPECT_FLOAT_EQ(scene.hair[0].strand_width[0], 0.01f);
  EXPECT_GT(scene.hair[0].bounds.min.y, 4.0f);
}

TEST(SceneErrors, AssetErrorsNameTheAssetAndTheSceneEntry) {
  TempDir dir;
  const std::string camera = R"("cameras": [{"position": [0,0,3], "target": [0,0,0], "vertical_fov_deg": 45, "near": 0.1, "far": 10}])";
  testing::write_text(dir / "scene.json",
                      R"({"version": 1, "volumes": [{"file": "assets/missing.vdb", "grid": "density", "extinction_scale": 1}], )" +
                          camera + "}");
  EXPECT_THAT(load_error_of([&] { load_scene(dir / "scene.json"); }),
              AllOf(StartsWith((dir / "assets/missing.vdb").string() + ": file not found"),
                    HasSubstr("(referenced by " + (dir / "scene.json").string() + " at volumes[0])")));
  testing::write_text(dir / "bad.hair", "HAIR but far too short");
  testing::write_text(dir / "scene.json", R"({"version": 1, "hair": [{"file": "bad.hair"}], )" + camera + "}");
  EXPECT_THAT(load_error_of([&] { load_scene(dir / "scene.json"); }),
              AllOf(HasSubstr("bad.hair: file is truncated"), HasSubstr("at hair[0])")));
}

}  // namespace
}  // namespace scene_test
}  // namespace avsm::scene
