// glTF as exporters write it: KHR_texture_transform, KHR_mesh_quantization,
// KHR_lights_punctual, cameras, and warnings for what is left out (extensions used but
// not read, skins, morph targets, animations). Real files from Debian's
// assimp-testmodels, generated ones for exact values.
#include "support.h"

#include "scene/gltf.h"
#include "scene/scene.h"

#include <gmock/gmock.h>
#include <nlohmann/json.hpp>

#include <glm/gtc/constants.hpp>

#include <cmath>
#include <cstring>

namespace avsm::scene {
namespace gltf_extensions_test {  // one per file: test targets are unity builds
namespace {

using json = nlohmann::json;
using ::testing::HasSubstr;
using testing::TempDir;

bool has_warning(const std::vector<std::string>& warnings, const std::string& text) {
  for (const std::string& warning : warnings)
    if (warning.find(text) != std::string::npos) return true;
  return false;
}

// A unit quad in the XY plane (node 0) whose POSITION and TEXCOORD_0/1 accessors hold
// positions as `position_type` (float, or shorts for KHR_mesh_quantization), +Z normals
// and the UVs below; `edit` may change the JSON.
// UVs: TEXCOORD_0 (0,0) (1,0) (1,1) (0,1); TEXCOORD_1 the same times 2.
std::filesystem::path write_quad(const TempDir& dir, const std::function<void(json&)>& edit,
                                 int position_type = 5126, bool normalized = false) {
  std::vector<std::byte> bin;
  auto append = [&](const void* data, std::size_t bytes) {
    const std::size_t offset = bin.size();
    bin.resize(offset + ((bytes + 3) & ~std::size_t(3)));  // keep views 4-byte aligned
    std::memcpy(bin.data() + offset, data, bytes);
    return offset;
  };
  json views = json::array();
  std::size_t position_bytes = 0, position_offset = 0;
  if (position_type == 5126) {
    const float p[12] = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
    position_offset = append(p, position_bytes = sizeof p);
  } else {  // shorts, 4-byte aligned elements as KHR_mesh_quantization asks: x y z pad
    const std::int16_t p[16] = {0, 0, 0, 0, 32767, 0, 0, 0, 32767, 32767, 0, 0, 0, 32767, 0, 0};
    position_offset = append(p, position_bytes = sizeof p);
  }
  const float uv0[8] = {0, 0, 1, 0, 1, 1, 0, 1};
  const float uv1[8] = {0, 0, 2, 0, 2, 2, 0, 2};
  const std::uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  const float normals[12] = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::size_t uv0_offset = append(uv0, sizeof uv0), uv1_offset = append(uv1, sizeof uv1);
  const std::size_t normal_offset = append(normals, sizeof normals);
  const std::size_t index_offset = append(indices, sizeof indices);
  json position_view = {{"buffer", 0}, {"byteOffset", position_offset}, {"byteLength", position_bytes}};
  if (position_type != 5126) position_view["byteStride"] = 8;
  json position_accessor = {{"bufferView", 0}, {"componentType", position_type}, {"count", 4}, {"type", "VEC3"}};
  if (normalized) position_accessor["normalized"] = true;
  testing::write_bytes(dir / "quad.bin", bin);
  json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}, {"name", "quad"}}}},
      {"meshes", {{{"primitives", {{{"attributes", {{"POSITION", 0}, {"TEXCOORD_0", 1}, {"TEXCOORD_1", 2}, {"NORMAL", 4}}}, {"indices", 3}}}}}}},
      {"accessors",
       {position_accessor,
        {{"bufferView", 1}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 2}, {"componentType", 5126}, {"count", 4}, {"type", "VEC2"}},
        {{"bufferView", 3}, {"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}},
        {{"bufferView", 4}, {"componentType", 5126}, {"count", 4}, {"type", "VEC3"}}}},
      {"bufferViews",
       {position_view,
        {{"buffer", 0}, {"byteOffset", uv0_offset}, {"byteLength", sizeof uv0}},
        {{"buffer", 0}, {"byteOffset", uv1_offset}, {"byteLength", sizeof uv1}},
        {{"buffer", 0}, {"byteOffset", index_offset}, {"byteLength", sizeof indices}},
        {{"buffer", 0}, {"byteOffset", normal_offset}, {"byteLength", sizeof normals}}}},
      {"buffers", {{{"uri", "quad.bin"}, {"byteLength", bin.size()}}}}};
  if (edit) edit(gltf);
  testing::write_text(dir / "quad.gltf", gltf.dump());
  return dir / "quad.gltf";
}

// The quad with a textured material whose base colour carries `transform`.
std::filesystem::path write_transformed_quad(const TempDir& dir, const json& transform) {
  std::filesystem::copy_file(testing::assimp_model("glTF2/BoxTextured-glTF/CesiumLogoFlat.png"), dir / "image.png");
  return write_quad(dir, [&](json& gltf) {
    gltf["extensionsUsed"] = {"KHR_texture_transform"};
    gltf["meshes"][0]["primitives"][0]["material"] = 0;
    gltf["materials"] = {{{"pbrMetallicRoughness",
                           {{"baseColorTexture", {{"index", 0}, {"extensions", {{"KHR_texture_transform", transform}}}}}}}}};
    gltf["textures"] = {{{"source", 0}}};
    gltf["images"] = {{{"uri", "image.png"}}};
  });
}

void expect_uvs(const Mesh& mesh, const std::vector<glm::vec2>& expected) {
  ASSERT_EQ(mesh.uvs.size(), expected.size());
  for (std::size_t i = 0; i < expected.size(); ++i) {
    EXPECT_NEAR(mesh.uvs[i].x, expected[i].x, 1e-5f) << "vertex " << i;
    EXPECT_NEAR(mesh.uvs[i].y, expected[i].y, 1e-5f) << "vertex " << i;
  }
}

TEST(GltfTextureTransform, OffsetRotationAndScaleAreBakedIntoTheUvs) {
  TempDir dir;
  // The extension's matrix T(offset) R(rotation) S(scale): with rotation pi/2, (u, v)
  // scaled to (2u, 3v) turns to (3v, -2u) (the direction TextureTransformTest marks
  // correct), then moves by the offset.
  const GltfAsset asset = load_gltf(write_transformed_quad(dir, {{"offset", {0.5, 0.25}}, {"rotation", glm::half_pi<double>()},
                                                                 {"scale", {2, 3}}}));
  ASSERT_EQ(asset.meshes.size(), 1u);
  expect_uvs(asset.meshes[0], {{0.5f, 0.25f}, {0.5f, -1.75f}, {3.5f, -1.75f}, {3.5f, 0.25f}});
  EXPECT_FALSE(has_warning(asset.warnings, "KHR_texture_transform")) << "it is read, not ignored";
}

TEST(GltfTextureTransform, ItsTexCoordPicksTheUvSet) {
  TempDir dir;
  const GltfAsset asset = load_gltf(write_transformed_quad(dir, {{"texCoord", 1}}));
  expect_uvs(asset.meshes[0], {{0, 0}, {2, 0}, {2, 2}, {0, 2}});
}

TEST(GltfTextureTransform, KhronosTestModelsOffsetsLandWhereItsReadmeSays) {
  const auto file = testing::assimp_model("glTF2/textureTransform/TextureTransformTest.gltf");
  AVSM_REQUIRE_FILE(file);
  const GltfAsset asset = load_gltf(file);
  EXPECT_FALSE(has_warning(asset.warnings, "KHR_texture_transform"));
  // The top row's quads have UVs (0, 0) to (0.5, 0.5), offset by (0.5, 0), (0, 0.5), (0.5, 0.5).
  const std::map<std::string, glm::vec2> offsets = {{"Offset U", {0.5f, 0.0f}}, {"Offset V", {0.0f, 0.5f}}, {"Offset UV", {0.5f, 0.5f}}};
  int checked = 0;
  for (const Mesh& mesh : asset.meshes) {
    const auto offset = offsets.find(asset.materials[mesh.material].name);
    if (offset == offsets.end()) continue;
    ++checked;
    for (const glm::vec2& uv : mesh.uvs) {
      EXPECT_GE(uv.x, offset->second.x - 1e-4f) << offset->first;
      EXPECT_LE(uv.x, offset->second.x + 0.5f + 1e-4f) << offset->first;
      EXPECT_GE(uv.y, offset->second.y - 1e-4f) << offset->first;
      EXPECT_LE(uv.y, offset->second.y + 0.5f + 1e-4f) << offset->first;
    }
  }
  EXPECT_EQ(checked, 3);
}

TEST(GltfQuantization, NormalizedShortPositionsLoadWhenTheFileUsesTheExtension) {
  TempDir dir;
  const auto file = write_quad(dir, [](json& gltf) { gltf["extensionsUsed"] = {"KHR_mesh_quantization"};
                                                     gltf["extensionsRequired"] = {"KHR_mesh_quantization"};
                                                     gltf["nodes"][0]["scale"] = {2, 2, 2}; },
                               5122, true);
  const GltfAsset asset = load_gltf(file);
  ASSERT_EQ(asset.meshes.size(), 1u);
  EXPECT_NEAR(asset.bounds.max.x, 2.0f, 1e-4f);  // 32767 normalized is 1, times the node's dequantizing scale
  EXPECT_NEAR(asset.bounds.max.y, 2.0f, 1e-4f);
}

TEST(GltfQuantization, QuantizedPositionsWithoutTheExtensionAreRefusedNamingIt) {
  TempDir dir;
  const auto file = write_quad(dir, {}, 5122, true);
  EXPECT_THAT(testing::load_error_of([&] { load_gltf(file); }), HasSubstr("KHR_mesh_quantization"));
}

// Three nodes, each placing one light: a sun turned 90 degrees about X (so it shines
// down -Y), a point light and a spot light whose cone is wider than ours can be.
json punctual_lights() {
  return {{"lights",
           {{{"name", "SunLight"}, {"type", "directional"}, {"intensity", 3.0}, {"color", {1, 0.9, 0.8}}},
            {{"type", "point"}, {"intensity", 100.0}, {"range", 8.0}},
            {{"name", "spot"}, {"type", "spot"}, {"intensity", 50.0}, {"spot", {{"innerConeAngle", 0.2}, {"outerConeAngle", 1.5707963}}}}}}};
}

std::filesystem::path write_lit_quad(const TempDir& dir) {
  return write_quad(dir, [](json& gltf) {
    gltf["extensionsUsed"] = {"KHR_lights_punctual"};
    gltf["extensions"] = {{"KHR_lights_punctual", punctual_lights()}};
    const double s = std::sqrt(0.5);
    gltf["nodes"].push_back({{"name", "Sun"}, {"rotation", {-s, 0, 0, s}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
    gltf["nodes"].push_back({{"translation", {1, 2, 3}}, {"extensions", {{"KHR_lights_punctual", {{"light", 1}}}}}});
    gltf["nodes"].push_back({{"translation", {0, 5, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 2}}}}}});
    gltf["scenes"][0]["nodes"] = {0, 1, 2, 3};
  });
}

TEST(GltfLights, PunctualLightsArePlacedNamedAndConverted) {
  TempDir dir;
  const GltfAsset asset = load_gltf(write_lit_quad(dir));
  ASSERT_EQ(asset.lights.size(), 3u);
  const Light& sun = asset.lights[0];
  EXPECT_EQ(sun.name, "Sun");  // the node's name first
  EXPECT_EQ(sun.type, LightType::directional);
  EXPECT_NEAR(sun.direction.y, -1.0f, 1e-5f);  // -Z turned by -90 degrees about X
  EXPECT_NEAR(sun.intensity, 3.0f / glm::pi<float>(), 1e-6f);  // lux / pi: what a white surface reflects
  EXPECT_FLOAT_EQ(sun.color.g, 0.9f);
  const Light& point = asset.lights[1];
  EXPECT_EQ(point.name, "light 1");
  EXPECT_EQ(point.type, LightType::point);
  EXPECT_EQ(point.position, glm::vec3(1, 2, 3));
  EXPECT_FLOAT_EQ(point.range, 8.0f);
  const Light& spot = asset.lights[2];
  EXPECT_EQ(spot.name, "spot");
  EXPECT_EQ(spot.type, LightType::spot);
  EXPECT_NEAR(spot.outer_cone_angle, glm::radians(89.0f), 1e-5f) << "a 90-degree cone is narrowed to what a map can hold";
  EXPECT_FLOAT_EQ(spot.inner_cone_angle, 0.2f);
  EXPECT_NEAR(spot.direction.z, -1.0f, 1e-6f);
}

TEST(GltfLights, ABadLightIndexIsALoadError) {
  TempDir dir;
  const auto file = write_quad(dir, [](json& gltf) {
    gltf["extensions"] = {{"KHR_lights_punctual", punctual_lights()}};
    gltf["nodes"][0]["extensions"] = {{"KHR_lights_punctual", {{"light", 7}}}};
  });
  EXPECT_THAT(testing::load_error_of([&] { load_gltf(file); }), HasSubstr("uses light 7"));
}

TEST(GltfCameras, KhronosCamerasGivesItsPerspectiveCameraAndWarnsOfTheOrthographicOne) {
  const auto file = testing::assimp_model("glTF2/cameras/Cameras.gltf");
  AVSM_REQUIRE_FILE(file);
  const GltfAsset asset = load_gltf(file);
  ASSERT_EQ(asset.cameras.size(), 1u);
  const Camera& camera = asset.cameras[0];
  EXPECT_EQ(camera.name, "camera 0");
  EXPECT_EQ(camera.position, glm::vec3(0.5f, 0.5f, 3.0f));
  const glm::vec3 forward = glm::normalize(camera.target - camera.position);
  EXPECT_NEAR(forward.z, -1.0f, 1e-6f);  // the node's -Z
  EXPECT_NEAR(camera.target.z, asset.bounds.center().z, 1e-4f) << "the target is where the view passes the asset's centre";
  EXPECT_FLOAT_EQ(camera.vertical_fov, 0.7f);
  EXPECT_FLOAT_EQ(camera.near_plane, 0.01f);
  EXPECT_FLOAT_EQ(camera.far_plane, 100.0f);
  EXPECT_TRUE(has_warning(asset.warnings, "camera 1 is orthographic"));
}

TEST(GltfWarnings, SkinsAndMorphTargetsAreNamed) {
  const auto skin = testing::assimp_model("glTF2/simple_skin/simple_skin.gltf");
  const auto morph = testing::assimp_model("glTF2/glTF-Sample-Models/AnimatedMorphCube-glTF/AnimatedMorphCube.gltf");
  AVSM_REQUIRE_FILE(skin);
  AVSM_REQUIRE_FILE(morph);
  const GltfAsset skinned = load_gltf(skin);
  EXPECT_TRUE(has_warning(skinned.warnings, "skin 0 of simple_skin.gltf is shown in its bind pose"));
  EXPECT_FALSE(has_warning(skinned.warnings, "animation")) << "its one animation plays (it turns a joint, which only the skin follows)";
  const GltfAsset morphed = load_gltf(morph);
  EXPECT_TRUE(has_warning(morphed.warnings, "has 2 morph targets; it is shown without them"));
}

TEST(GltfWarnings, AnExtensionUsedButNotReadIsNamedWithWhatIsLeftOut) {
  TempDir dir;
  const GltfAsset asset = load_gltf(write_quad(dir, [](json& gltf) {
    gltf["extensionsUsed"] = {"KHR_materials_clearcoat", "EXT_made_up"};
  }));
  EXPECT_TRUE(has_warning(asset.warnings, "uses extension KHR_materials_clearcoat, which is not supported: the clear-coat layer"));
  EXPECT_TRUE(has_warning(asset.warnings, "uses extension EXT_made_up, which is not supported: it is ignored"));
}

// ---- samplers and mips ----

TEST(GltfSamplers, TheFilesSamplersAreKeptAndMipsMadeWhereTheyAreRead) {
  const auto clamped = testing::assimp_model("glTF2/textureTransform/TextureTransformTest.gltf");
  AVSM_REQUIRE_FILE(clamped);
  const GltfAsset test = load_gltf(clamped);
  ASSERT_EQ(test.textures.size(), 5u);
  for (const Texture& texture : test.textures) {
    if (texture.name != "UV.png" && texture.name != "Arrow.png") {  // the markers: no sampler, the defaults
      EXPECT_EQ(texture.sampler, TextureSampler{}) << texture.name;
      EXPECT_FALSE(texture.mips.empty()) << texture.name;
      continue;
    }
    // UV and Arrow read through sampler 0: clamp, linear, no mips.
    EXPECT_EQ(texture.sampler.wrap_u, TextureWrap::clamp_to_edge);
    EXPECT_EQ(texture.sampler.wrap_v, TextureWrap::clamp_to_edge);
    EXPECT_EQ(texture.sampler.min, TextureFilter::linear);
    EXPECT_FALSE(texture.sampler.mipmapped);
    EXPECT_TRUE(texture.mips.empty());
  }
  const GltfAsset blender = load_gltf(testing::project_content("examples/assets/blender_room.gltf"));
  ASSERT_EQ(blender.textures.size(), 1u);  // minFilter LINEAR_MIPMAP_LINEAR, wrap unset: repeat
  const Texture& checker = blender.textures[0];
  EXPECT_EQ(checker.sampler.wrap_u, TextureWrap::repeat);
  EXPECT_TRUE(checker.sampler.mipmapped);
  EXPECT_EQ(checker.sampler.mip, TextureFilter::linear);
  EXPECT_EQ(checker.mip_levels(), 7u);  // 64 x 64 down to 1 x 1
}

TEST(GltfSamplers, MipsAverageInLinearLightAndFoldOddEdges) {
  Texture texture;
  texture.width = 3;  // an odd width: level 1 is 1 x 1 and takes all three columns
  texture.height = 2;
  texture.color_space = ColorSpace::srgb;
  texture.rgba8 = {0, 0, 0, 0, 255, 255, 255, 255, 0, 0, 0, 0,  // black, white, black
                   255, 255, 255, 255, 0, 0, 0, 0, 255, 255, 255, 255};
  generate_mips(texture);
  ASSERT_EQ(texture.mips.size(), 1u);
  ASSERT_EQ(texture.mips[0].size(), 4u);
  // 3 of 6 texels white: linear 0.5, which sRGB encodes as 188 (averaging bytes would give 128).
  EXPECT_EQ(texture.mips[0][0], 188);
  EXPECT_EQ(texture.mips[0][3], 128) << "alpha is linear";

  texture.color_space = ColorSpace::linear;
  generate_mips(texture);
  EXPECT_EQ(texture.mips[0][0], 128);

  Texture square;
  square.width = square.height = 8;
  square.rgba8.assign(8 * 8 * 4, 77);
  generate_mips(square);
  EXPECT_EQ(square.mip_levels(), 4u);  // 8, 4, 2, 1
  for (std::uint32_t level = 1; level < square.mip_levels(); ++level)
    EXPECT_EQ(square.mips[level - 1].size(), std::size_t(square.level_width(level)) * square.level_height(level) * 4);
  EXPECT_EQ(square.mips.back()[0], 77) << "a flat image stays flat";
}

TEST(GltfSamplers, AnUnknownWrapModeIsALoadErrorNamingTheSampler) {
  TempDir dir;
  std::filesystem::copy_file(testing::assimp_model("glTF2/BoxTextured-glTF/CesiumLogoFlat.png"), dir / "image.png");
  const auto file = write_quad(dir, [](json& gltf) {
    gltf["meshes"][0]["primitives"][0]["material"] = 0;
    gltf["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    gltf["textures"] = {{{"source", 0}, {"sampler", 0}}};
    gltf["samplers"] = {{{"wrapS", 1234}}};
    gltf["images"] = {{{"uri", "image.png"}}};
  });
  EXPECT_THAT(testing::load_error_of([&] { load_gltf(file); }), HasSubstr("sampler 0: unknown wrapS 1234"));
}

// ---- node animation ----

// The quad (node 0) slides 4 m along X over 2 s (LINEAR) and turns a quarter about Y at
// 1 s (STEP); a child node carries a point light 1 m above it.
std::filesystem::path write_animated_quad(const TempDir& dir) {
  const float times[2] = {0.0f, 2.0f}, steps[2] = {0.0f, 1.0f};
  const float translations[6] = {0, 0, 0, 4, 0, 0};
  const float s = std::sqrt(0.5f);
  const float rotations[8] = {0, 0, 0, 1, 0, s, 0, s};
  std::vector<std::byte> bin(sizeof times + sizeof steps + sizeof translations + sizeof rotations);
  std::size_t offset = 0;
  json views = json::array();
  for (auto [data, bytes] : {std::pair<const void*, std::size_t>{times, sizeof times}, {steps, sizeof steps},
                             {translations, sizeof translations}, {rotations, sizeof rotations}}) {
    std::memcpy(bin.data() + offset, data, bytes);
    views.push_back({{"buffer", 1}, {"byteOffset", offset}, {"byteLength", bytes}});
    offset += bytes;
  }
  testing::write_bytes(dir / "anim.bin", bin);
  return write_quad(dir, [&](json& gltf) {
    const int first_view = int(gltf["bufferViews"].size()), first_accessor = int(gltf["accessors"].size());
    for (const json& view : views) gltf["bufferViews"].push_back(view);
    gltf["buffers"].push_back({{"uri", "anim.bin"}, {"byteLength", bin.size()}});
    const std::pair<int, const char*> accessors[] = {{1, "SCALAR"}, {1, "SCALAR"}, {3, "VEC3"}, {4, "VEC4"}};
    for (int i = 0; i < 4; ++i)
      gltf["accessors"].push_back({{"bufferView", first_view + i}, {"componentType", 5126}, {"count", 2}, {"type", accessors[i].second}});
    gltf["animations"] = {{{"name", "slide"},
                           {"samplers", {{{"input", first_accessor}, {"output", first_accessor + 2}, {"interpolation", "LINEAR"}},
                                         {{"input", first_accessor + 1}, {"output", first_accessor + 3}, {"interpolation", "STEP"}}}},
                           {"channels", {{{"sampler", 0}, {"target", {{"node", 0}, {"path", "translation"}}}},
                                         {{"sampler", 1}, {"target", {{"node", 0}, {"path", "rotation"}}}}}}}};
    gltf["extensions"] = {{"KHR_lights_punctual", {{"lights", {{{"type", "point"}, {"intensity", 10.0}}}}}}};
    gltf["nodes"][0]["children"] = {1};
    gltf["nodes"].push_back({{"name", "lamp"}, {"translation", {0, 1, 0}}, {"extensions", {{"KHR_lights_punctual", {{"light", 0}}}}}});
  });
}

TEST(GltfAnimation, NodeChannelsMoveMeshesAndTheLightsOnTheirNodes) {
  TempDir dir;
  const GltfAsset asset = load_gltf(write_animated_quad(dir));
  ASSERT_TRUE(asset.nodes && asset.nodes->animated());
  EXPECT_FLOAT_EQ(asset.nodes->end(), 2.0f);
  EXPECT_EQ(asset.mesh_nodes, std::vector<int>{0});
  EXPECT_EQ(asset.light_nodes, std::vector<int>{1});
  const glm::mat4 half = asset.nodes->world(1, 0.5f);  // the lamp: 1 m along X, not yet turned
  EXPECT_NEAR(half[3].x, 1.0f, 1e-5f);
  EXPECT_NEAR(half[3].y, 1.0f, 1e-5f);
  const glm::mat4 turned = asset.nodes->world(0, 1.5f);  // a quarter turn about Y: +X goes to -Z
  EXPECT_NEAR(turned[0].z, -1.0f, 1e-5f);
  EXPECT_NEAR(turned[3].x, 3.0f, 1e-5f);

  // Placed 10 m along Z by the scene file: the nodes move under that placement.
  testing::write_text(dir / "shot.scene.json", R"({"version": 1,
    "models": [{"name": "quad", "file": "quad.gltf", "transform": {"translation": [0, 0, 10]}}],
    "cameras": [{"position": [0, 1, 5], "target": [0, 0, 0], "vertical_fov_deg": 45, "near": 0.1, "far": 50}]})");
  Scene scene = load_scene(dir / "shot.scene.json");
  ASSERT_EQ(scene.animation.models.size(), 1u);
  // The unit quad in the XY plane, turned edge-on to X from 1 s: it reaches x = 3 just
  // before (2 m along), x = 4 at the end.
  EXPECT_GE(scene.bounds.max.x, 4.0f - 1e-4f) << "the bounds hold the quad's whole slide";
  scene.animation.pose(scene, 1.0f);  // 2 m along, turned: x = 2, z from 9 to 10
  EXPECT_NEAR(scene.meshes[0].bounds.min.x, 2.0f, 1e-5f);
  EXPECT_NEAR(scene.meshes[0].bounds.max.x, 2.0f, 1e-5f);
  EXPECT_NEAR(scene.meshes[0].bounds.min.z, 9.0f, 1e-5f);
  EXPECT_NEAR(scene.meshes[0].bounds.max.z, 10.0f, 1e-5f);
  ASSERT_EQ(scene.lights.size(), 1u);
  EXPECT_NEAR(scene.lights[0].position.x, 2.0f, 1e-5f);
  EXPECT_NEAR(scene.lights[0].position.y, 1.0f, 1e-5f);
  EXPECT_NEAR(scene.lights[0].position.z, 10.0f, 1e-5f);
}

TEST(GltfAnimation, AChannelWithTooFewValuesIsALoadError) {
  TempDir dir;
  const auto file = write_animated_quad(dir);
  const std::vector<std::byte> bytes = testing::read_bytes(file);
  json gltf = json::parse(reinterpret_cast<const char*>(bytes.data()), reinterpret_cast<const char*>(bytes.data()) + bytes.size());
  gltf["accessors"][int(gltf["accessors"].size()) - 2]["count"] = 1;  // the translations
  testing::write_text(file, gltf.dump());
  EXPECT_THAT(testing::load_error_of([&] { load_gltf(file); }), HasSubstr("animation 0 channel 0: 1 output values for 2 keys"));
}

// ---- in a scene file ----

// A scene of one model, with one camera of its own unless `with_camera` is false.
std::filesystem::path write_scene(const TempDir& dir, const json& model, bool with_camera = true) {
  json scene = {{"version", 1}, {"models", {model}}};
  if (with_camera)
    scene["cameras"] = {{{"position", {0, 0, 5}}, {"target", {0, 0, 0}}, {"vertical_fov_deg", 45}, {"near", 0.1}, {"far", 50}}};
  testing::write_text(dir / "lit.scene.json", scene.dump());
  return dir / "lit.scene.json";
}

TEST(GltfLightsInScenes, FileLightsJoinRenamedAndTheSceneChangesOrDropsThemByName) {
  TempDir dir;
  write_lit_quad(dir);
  json model = {{"name", "room"}, {"file", "quad.gltf"},
                {"lights", {{"Sun", {{"intensity", 2.5}, {"shadow", {{"resolution", 512}}}}}, {"spot", "off"}}}};
  const Scene scene = load_scene(write_scene(dir, model));
  ASSERT_EQ(scene.lights.size(), 2u);
  EXPECT_EQ(scene.lights[0].name, "room/Sun");
  EXPECT_FLOAT_EQ(scene.lights[0].intensity, 2.5f);
  EXPECT_EQ(scene.lights[0].shadow.resolution, 512);
  EXPECT_EQ(scene.lights[1].name, "room/light 1");
  EXPECT_EQ(scene.lights[1].shadow.resolution, ShadowSettings{}.resolution);

  model["lights"] = "off";
  EXPECT_TRUE(load_scene(write_scene(dir, model)).lights.empty());
}

TEST(GltfLightsInScenes, AnOverrideOfALightTheFileLacksNamesItsPathAndTheLights) {
  TempDir dir;
  write_lit_quad(dir);
  const auto scene = write_scene(dir, {{"file", "quad.gltf"}, {"lights", {{"Moon", "off"}}}});
  const std::string error = testing::load_error_of([&] { load_scene(scene); });
  EXPECT_THAT(error, HasSubstr("no KHR_lights_punctual light named 'Moon'"));
  EXPECT_THAT(error, HasSubstr("'Sun'"));
  EXPECT_THAT(error, HasSubstr("models[0].lights.Moon"));
}

TEST(GltfCamerasInScenes, ASceneWithoutCamerasTakesItsModelsOnesOrSaysItHasNone) {
  const auto cameras = testing::assimp_model("glTF2/cameras/Cameras.gltf");
  AVSM_REQUIRE_FILE(cameras);
  TempDir dir;
  const Scene scene = load_scene(write_scene(dir, {{"name", "shot"}, {"file", cameras.string()}}, false));
  ASSERT_EQ(scene.cameras.size(), 1u);
  EXPECT_EQ(scene.cameras[0].name, "shot/camera 0");

  write_quad(dir, {});
  EXPECT_THAT(testing::load_error_of([&] { load_scene(write_scene(dir, {{"file", "quad.gltf"}}, false)); }),
              HasSubstr("a scene needs at least one camera, and its models' glTF files have none"));
}

}  // namespace
}  // namespace gltf_extensions_test
}  // namespace avsm::scene
