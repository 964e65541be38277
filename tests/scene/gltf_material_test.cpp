// glTF metallic-roughness materials: factors, the five textures each decoded in its
// colour space, one UV set per material, KHR_texture_transform, and tangents (the
// file's, transformed with the node; else generated from UV derivatives).
#include "support.h"

#include "scene/gltf.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <cstring>

namespace avsm::scene {
namespace gltf_material_test {  // one per file: test targets are unity builds
namespace {

using testing::TempDir;
using json = nlohmann::json;

// A unit quad in the XY plane facing +Z (.gltf + .bin) with NORMAL and TEXCOORD_0
// (glTF's V runs down the image: the quad's top edge has V = 0), optionally TANGENT,
// and one material whose textures all use image 0 (a copy of a Khronos PNG);
// `edit` may change the JSON before it is written. Written into `dir`, created if needed.
std::filesystem::path write_quad_gltf(const std::filesystem::path& dir, const std::function<void(json&)>& edit,
                                      std::vector<float> uvs = {0, 1, 1, 1, 1, 0, 0, 0},
                                      std::vector<float> tangents = {}) {
  const auto png = testing::assimp_model("glTF2/BoxTextured-glTF/CesiumLogoFlat.png");
  std::filesystem::create_directories(dir);
  std::filesystem::copy_file(png, dir / "image.png");
  const std::vector<float> positions = {0, 0, 0, 1, 0, 0, 1, 1, 0, 0, 1, 0};
  const std::vector<float> normals = {0, 0, 1, 0, 0, 1, 0, 0, 1, 0, 0, 1};
  const std::uint16_t indices[6] = {0, 1, 2, 0, 2, 3};
  std::vector<std::byte> bin;
  json views = json::array(), accessors = json::array(), attributes = json::object();
  auto add = [&](const void* data, std::size_t bytes, json accessor) {
    views.push_back({{"buffer", 0}, {"byteOffset", bin.size()}, {"byteLength", bytes}});
    accessor["bufferView"] = views.size() - 1;
    accessors.push_back(accessor);
    bin.resize(bin.size() + bytes);
    std::memcpy(bin.data() + bin.size() - bytes, data, bytes);
    return int(accessors.size() - 1);
  };
  attributes["POSITION"] = add(positions.data(), positions.size() * 4, {{"componentType", 5126}, {"count", 4}, {"type", "VEC3"}});
  attributes["NORMAL"] = add(normals.data(), normals.size() * 4, {{"componentType", 5126}, {"count", 4}, {"type", "VEC3"}});
  attributes["TEXCOORD_0"] = add(uvs.data(), uvs.size() * 4, {{"componentType", 5126}, {"count", 4}, {"type", "VEC2"}});
  if (!tangents.empty())
    attributes["TANGENT"] = add(tangents.data(), tangents.size() * 4, {{"componentType", 5126}, {"count", 4}, {"type", "VEC4"}});
  const int index_accessor = add(indices, sizeof indices, {{"componentType", 5123}, {"count", 6}, {"type", "SCALAR"}});
  testing::write_bytes(dir / "quad.bin", bin);
  json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"mesh", 0}}}},
      {"meshes", {{{"name", "quad"}, {"primitives", {{{"attributes", attributes}, {"indices", index_accessor}, {"material", 0}}}}}}},
      {"materials", {{{"name", "m"}}}},
      {"textures", {{{"source", 0}}}},
      {"images", {{{"uri", "image.png"}}}},
      {"accessors", accessors},
      {"bufferViews", views},
      {"buffers", {{{"uri", "quad.bin"}, {"byteLength", bin.size()}}}}};
  if (edit) edit(gltf);
  testing::write_text(dir / "quad.gltf", gltf.dump());
  return dir / "quad.gltf";
}

void expect_near(const glm::vec3& got, const glm::vec3& expected, float tolerance = 1e-5f) {
  for (int c = 0; c < 3; ++c) EXPECT_NEAR(got[c], expected[c], tolerance) << "component " << c;
}

TEST(GltfMaterial, FactorsAndEveryTextureInItsColourSpace) {
  TempDir dir;
  const GltfAsset asset = load_gltf(write_quad_gltf(dir.path(), [](json& g) {
    g["materials"][0] = {{"name", "m"},
                         {"pbrMetallicRoughness",
                          {{"baseColorTexture", {{"index", 0}}},
                           {"metallicFactor", 0.25},
                           {"roughnessFactor", 0.75},
                           {"metallicRoughnessTexture", {{"index", 0}}}}},
                         {"normalTexture", {{"index", 0}, {"scale", 0.5}}},
                         {"occlusionTexture", {{"index", 0}, {"strength", 0.3}}},
                         {"emissiveTexture", {{"index", 0}}},
                         {"emissiveFactor", {1.0, 0.5, 0.25}}};
  }));
  ASSERT_EQ(asset.materials.size(), 1u);
  const Material& m = asset.materials[0];
  EXPECT_FLOAT_EQ(m.metallic_factor, 0.25f);
  EXPECT_FLOAT_EQ(m.roughness_factor, 0.75f);
  EXPECT_FLOAT_EQ(m.normal_scale, 0.5f);
  EXPECT_FLOAT_EQ(m.occlusion_strength, 0.3f);
  expect_near(m.emissive, {1.0f, 0.5f, 0.25f});
  // One image used as colour and as data: one texture per colour space, shared within each.
  ASSERT_EQ(asset.textures.size(), 2u);
  EXPECT_EQ(asset.textures[m.base_color_texture].color_space, ColorSpace::srgb);
  EXPECT_EQ(m.emissive_texture, m.base_color_texture);
  EXPECT_EQ(asset.textures[m.metallic_roughness_texture].color_space, ColorSpace::linear);
  EXPECT_EQ(m.normal_texture, m.metallic_roughness_texture);
  EXPECT_EQ(m.occlusion_texture, m.metallic_roughness_texture);
  EXPECT_EQ(asset.textures[0].rgba8, asset.textures[1].rgba8);
  EXPECT_TRUE(asset.warnings.empty());
}

TEST(GltfMaterial, DefaultsAreTheSpecifications) {
  TempDir dir;
  const GltfAsset asset = load_gltf(write_quad_gltf(dir.path(), [](json& g) { g["materials"][0] = {{"name", "bare"}}; }));
  const Material& m = asset.materials.at(0);
  EXPECT_FLOAT_EQ(m.metallic_factor, 1.0f);
  EXPECT_FLOAT_EQ(m.roughness_factor, 1.0f);
  EXPECT_EQ(m.metallic_roughness_texture, -1);
  EXPECT_EQ(m.normal_texture, -1);
  EXPECT_TRUE(asset.meshes.at(0).tangents.empty());  // no normal texture: no tangents
}

TEST(GltfMaterial, FactorsOutsideTheirRangeAreClampedWithAWarning) {
  TempDir dir;
  const GltfAsset asset = load_gltf(write_quad_gltf(dir.path(), [](json& g) {
    g["materials"][0]["pbrMetallicRoughness"] = {{"metallicFactor", 1.5}, {"roughnessFactor", -0.5}};
  }));
  EXPECT_FLOAT_EQ(asset.materials.at(0).metallic_factor, 1.0f);
  EXPECT_FLOAT_EQ(asset.materials.at(0).roughness_factor, 0.0f);
  ASSERT_EQ(asset.warnings.size(), 2u);
  EXPECT_THAT(asset.warnings[0], AllOf(HasSubstr("material 'm'"), HasSubstr("metallicFactor"), HasSubstr("clamped")));
}

// One UV set per material: the first texture's; a texture on another set is dropped, said so.
TEST(GltfMaterial, ATextureOnAnotherUvSetIsDroppedWithAWarning) {
  TempDir dir;
  const GltfAsset asset = load_gltf(write_quad_gltf(dir.path(), [](json& g) {
    g["materials"][0]["pbrMetallicRoughness"] = {{"baseColorTexture", {{"index", 0}}}};
    g["materials"][0]["normalTexture"] = {{"index", 0}, {"texCoord", 1}};
  }));
  const Material& m = asset.materials.at(0);
  EXPECT_GE(m.base_color_texture, 0);
  EXPECT_EQ(m.normal_texture, -1);
  ASSERT_EQ(asset.warnings.size(), 1u);
  EXPECT_THAT(asset.warnings[0], AllOf(HasSubstr("material 'm'"), HasSubstr("normalTexture reads TEXCOORD_1"),
                                       HasSubstr("TEXCOORD_0"), HasSubstr("not applied")));
}

// Generated tangents follow +U; the handedness makes cross(N, T) x w point up the image
// (-V in glTF's UVs), so that a normal texture's +Y means "up" in the picture.
TEST(GltfMaterial, TangentsAreGeneratedFromUvDerivatives) {
  auto normal_mapped = [](json& g) { g["materials"][0]["normalTexture"] = {{"index", 0}}; };
  TempDir dir;
  const Mesh plain = load_gltf(write_quad_gltf(dir / "plain", normal_mapped)).meshes.at(0);
  ASSERT_EQ(plain.tangents.size(), plain.positions.size());
  for (std::size_t i = 0; i < plain.tangents.size(); ++i) {
    expect_near(glm::vec3(plain.tangents[i]), {1, 0, 0});
    EXPECT_EQ(plain.tangents[i].w, 1.0f);
    expect_near(glm::cross(plain.normals[i], glm::vec3(plain.tangents[i])) * plain.tangents[i].w, {0, 1, 0});
  }
  // U running the other way: the tangent turns round, the bitangent must not.
  const Mesh mirrored = load_gltf(write_quad_gltf(dir / "mirrored", normal_mapped, {1, 1, 0, 1, 0, 0, 1, 0})).meshes.at(0);
  for (std::size_t i = 0; i < mirrored.tangents.size(); ++i) {
    expect_near(glm::vec3(mirrored.tangents[i]), {-1, 0, 0});
    EXPECT_EQ(mirrored.tangents[i].w, -1.0f);
    expect_near(glm::cross(mirrored.normals[i], glm::vec3(mirrored.tangents[i])) * mirrored.tangents[i].w, {0, 1, 0});
  }
  // UVs rotated a quarter turn (U up the quad) and sheared positions: still unit and orthogonal.
  const Mesh rotated = load_gltf(write_quad_gltf(dir / "rotated", normal_mapped, {0, 0, 0, 1, 1, 1, 1, 0})).meshes.at(0);
  for (std::size_t i = 0; i < rotated.tangents.size(); ++i) {
    expect_near(glm::vec3(rotated.tangents[i]), {0, 1, 0});
    EXPECT_NEAR(glm::dot(glm::vec3(rotated.tangents[i]), rotated.normals[i]), 0.0f, 1e-6f);
  }
}

// The file's tangents are kept, turned with the node, their handedness flipped by a mirror.
TEST(GltfMaterial, FileTangentsFollowTheNodeTransform) {
  const std::vector<float> uvs = {0, 1, 1, 1, 1, 0, 0, 0};
  const std::vector<float> tangents = {1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1, 1, 0, 0, -1};  // deliberately left-handed
  TempDir dir;
  const Mesh turned = load_gltf(write_quad_gltf(dir / "turned", [](json& g) {
                                  g["materials"][0]["normalTexture"] = {{"index", 0}};
                                  g["nodes"][0]["rotation"] = {0, 0, std::sin(M_PI / 4), std::cos(M_PI / 4)};  // 90 deg about Z
                                }, uvs, tangents)).meshes.at(0);
  ASSERT_EQ(turned.tangents.size(), 4u);
  expect_near(glm::vec3(turned.tangents[0]), {0, 1, 0});
  EXPECT_EQ(turned.tangents[0].w, -1.0f);
  const Mesh mirrored = load_gltf(write_quad_gltf(dir / "mirrored", [](json& g) {
                                    g["materials"][0]["normalTexture"] = {{"index", 0}};
                                    g["nodes"][0]["scale"] = {-1, 1, 1};
                                  }, uvs, tangents)).meshes.at(0);
  expect_near(glm::vec3(mirrored.tangents[0]), {-1, 0, 0});
  EXPECT_EQ(mirrored.tangents[0].w, 1.0f);
}

TEST(GltfMaterial, NormalTextureWithoutUvsIsNotAppliedWithAWarning) {
  TempDir dir;
  const GltfAsset asset = load_gltf(write_quad_gltf(dir.path(), [](json& g) {
    g["materials"][0]["normalTexture"] = {{"index", 0}};
    g["meshes"][0]["primitives"][0]["attributes"].erase("TEXCOORD_0");
  }));
  EXPECT_TRUE(asset.meshes.at(0).tangents.empty());
  ASSERT_EQ(asset.warnings.size(), 1u);
  EXPECT_THAT(asset.warnings[0], AllOf(HasSubstr("quad"), HasSubstr("no texture coordinates")));
}

// Khronos' ClearCoatTest (assimp-testmodels): normal textures without TANGENT, a
// metallic-roughness texture, an emissive label texture.
TEST(GltfMaterial, KhronosClearCoatTestLoadsItsTexturesAndGetsTangents) {
  const auto file = testing::assimp_model("glTF2/ClearCoat-glTF/ClearCoatTest.gltf");
  AVSM_REQUIRE_FILE(file);
  const GltfAsset asset = load_gltf(file);
  int normal_mapped = 0, with_mr = 0, with_emissive = 0;
  for (const Material& m : asset.materials) {
    if (m.normal_texture >= 0) {
      ++normal_mapped;
      EXPECT_EQ(asset.textures.at(m.normal_texture).color_space, ColorSpace::linear) << m.name;
    }
    if (m.metallic_roughness_texture >= 0) {
      ++with_mr;
      EXPECT_EQ(asset.textures.at(m.metallic_roughness_texture).color_space, ColorSpace::linear) << m.name;
    }
    if (m.emissive_texture >= 0) {
      ++with_emissive;
      EXPECT_EQ(asset.textures.at(m.emissive_texture).color_space, ColorSpace::srgb) << m.name;
    }
  }
  EXPECT_EQ(normal_mapped, 6);  // BaseNorm_*, CoatNorm_Coating, SharedNorm_* (Base, Coated, Coating)
  EXPECT_EQ(with_mr, 1);        // RoughVariations_Coating
  EXPECT_EQ(with_emissive, 1);  // LabelMaterial
  int meshes_with_tangents = 0;
  for (const Mesh& mesh : asset.meshes) {
    const bool needs = asset.materials[mesh.material].normal_texture >= 0;
    ASSERT_EQ(mesh.tangents.size(), needs ? mesh.positions.size() : 0u) << mesh.name;
    meshes_with_tangents += needs;
    for (std::size_t i = 0; i < mesh.tangents.size(); ++i) {
      const glm::vec3 t(mesh.tangents[i]);
      ASSERT_NEAR(glm::length(t), 1.0f, 1e-4f) << mesh.name << " vertex " << i;
      ASSERT_NEAR(glm::dot(t, mesh.normals[i]), 0.0f, 1e-4f) << mesh.name << " vertex " << i;
      ASSERT_EQ(std::abs(mesh.tangents[i].w), 1.0f);
    }
  }
  EXPECT_GE(meshes_with_tangents, 6);
}

}  // namespace
}  // namespace gltf_material_test
}  // namespace avsm::scene
