// glTF: real files (Cornell box, Khronos / glTF-Asset-Generator samples from
// Debian's assimp-testmodels), generated files for exact checks, bad input.
#include "support.h"

#include "scene/gltf.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <cmath>
#include <limits>
#include <numeric>

namespace avsm::scene {
namespace gltf_test {  // one per file: test targets are unity builds
namespace {

using testing::TempDir;
using testing::load_error_of;
using json = nlohmann::json;

std::size_t total_triangles(const GltfAsset& asset) {
  std::size_t count = 0;
  for (const Mesh& mesh : asset.meshes) count += mesh.triangle_count();
  return count;
}

void expect_unit_normals(const GltfAsset& asset) {
  for (const Mesh& mesh : asset.meshes) {
    ASSERT_EQ(mesh.normals.size(), mesh.positions.size()) << mesh.name;
    for (const glm::vec3& n : mesh.normals) ASSERT_NEAR(glm::length(n), 1.0f, 1e-4f) << mesh.name;
  }
}

std::filesystem::path primitive_mode_model(int index) {
  char name[128];
  std::snprintf(name, sizeof name, "glTF2/glTF-Asset-Generator/Mesh_PrimitiveMode/Mesh_PrimitiveMode_%02d.gltf", index);
  return testing::assimp_model(name);
}

// A one-triangle glTF (.gltf + .bin) with a parent/child node pair, written in
// the test folder; `edit` may change the JSON before it is written.
std::filesystem::path write_triangle_gltf(const TempDir& dir, const std::function<void(json&)>& edit = {},
                                          std::vector<float> positions = {0, 0, 0, 1, 0, 0, 0, 1, 0}) {
  std::vector<std::byte> bin(positions.size() * 4 + 6);
  std::memcpy(bin.data(), positions.data(), positions.size() * 4);
  const std::uint16_t indices[3] = {0, 1, 2};
  std::memcpy(bin.data() + positions.size() * 4, indices, 6);
  testing::write_bytes(dir / "tri.bin", bin);
  json gltf = {
      {"asset", {{"version", "2.0"}}},
      {"scene", 0},
      {"scenes", {{{"nodes", {0}}}}},
      {"nodes", {{{"translation", {10, 0, 0}}, {"children", {1}}}, {{"mesh", 0}, {"scale", {1, 2, 1}}}}},
      {"meshes", {{{"name", "tri"}, {"primitives", {{{"attributes", {{"POSITION", 0}}}, {"indices", 1}}}}}}},
      {"accessors", {{{"bufferView", 0}, {"componentType", 5126}, {"count", positions.size() / 3}, {"type", "VEC3"}},
                     {{"bufferView", 1}, {"componentType", 5123}, {"count", 3}, {"type", "SCALAR"}}}},
      {"bufferViews", {{{"buffer", 0}, {"byteOffset", 0}, {"byteLength", positions.size() * 4}},
                       {{"buffer", 0}, {"byteOffset", positions.size() * 4}, {"byteLength", 6}}}},
      {"buffers", {{{"uri", "tri.bin"}, {"byteLength", bin.size()}}}}};
  if (edit) edit(gltf);
  testing::write_text(dir / "tri.gltf", gltf.dump());
  return dir / "tri.gltf";
}

TEST(Gltf, CornellBoxHasItsMeshesTrianglesAndMaterials) {
  const auto file = testing::shared_content("cornell_box/CornellBox.glb");
  AVSM_REQUIRE_FILE(file);
  const GltfAsset asset = load_gltf(file);
  // README: 4 meshes (one with 3 primitives -> 6 of ours), 36 triangles, 5 materials.
  EXPECT_EQ(asset.meshes.size(), 6u);
  EXPECT_EQ(total_triangles(asset), 36u);
  EXPECT_EQ(asset.materials.size(), 5u);
  expect_unit_normals(asset);
  // Node translations applied: the room spans x [-556, 0], y [0, 548.8], z [-559.2, 0].
  EXPECT_NEAR(asset.bounds.min.x, -556.0f, 0.1f);
  EXPECT_NEAR(asset.bounds.max.y, 548.8f, 0.1f);
  EXPECT_NEAR(asset.bounds.min.z, -559.2f, 0.1f);
  EXPECT_NEAR(asset.bounds.max.x, 0.0f, 0.1f);
  // The light: emissive 1 x KHR_materials_emissive_strength 100, double-sided.
  ASSERT_EQ(asset.meshes[0].name, "Light");  // node order, node names
  EXPECT_EQ(asset.meshes[5].name, "cornell.box#2");
  const Material& light = asset.materials[asset.meshes[0].material];
  EXPECT_EQ(light.name, "Emitter_Light_temp");
  EXPECT_FLOAT_EQ(light.emissive.r, 100.0f);
  EXPECT_TRUE(light.double_sided);
  EXPECT_EQ(light.alpha_mode, AlphaMode::opaque);
  EXPECT_TRUE(asset.line_strands.points.empty());
}

TEST(Gltf, ExternalEmbeddedAndBinaryTexturesDecodeToTheSamePixels) {
  const auto external = testing::assimp_model("glTF2/BoxTextured-glTF/BoxTextured.gltf");
  const auto embedded = testing::assimp_model("glTF2/BoxTextured-glTF-Embedded/BoxTextured.gltf");
  const auto binary = testing::assimp_model("glTF2/BoxTextured-glTF-Binary/BoxTextured.glb");
  for (const auto& file : {external, embedded, binary}) AVSM_REQUIRE_FILE(file);
  const GltfAsset a = load_gltf(external), b = load_gltf(embedded), c = load_gltf(binary);
  ASSERT_EQ(a.textures.size(), 1u);
  EXPECT_EQ(a.textures[0].width, 211u);  // CesiumLogoFlat.png, palette PNG -> RGBA8
  EXPECT_EQ(a.textures[0].height, 211u);
  EXPECT_EQ(a.textures[0].rgba8.size(), 211u * 211u * 4u);
  ASSERT_EQ(b.textures.size(), 1u);
  ASSERT_EQ(c.textures.size(), 1u);
  EXPECT_EQ(a.textures[0].rgba8, b.textures[0].rgba8);
  EXPECT_EQ(a.textures[0].rgba8, c.textures[0].rgba8);
  ASSERT_EQ(a.meshes.size(), 1u);
  EXPECT_EQ(a.materials[a.meshes[0].material].base_color_texture, 0);
  EXPECT_EQ(a.meshes[0].uvs.size(), a.meshes[0].positions.size());
  EXPECT_EQ(a.meshes[0].triangle_count(), 12u);
}

TEST(Gltf, JpegBaseColourTexturesDecodeToo) {
  const auto jpeg = testing::assimp_model("glTF2/ClearCoat-glTF/PlasticWrap_normals.jpg");
  AVSM_REQUIRE_FILE(jpeg);
  TempDir dir;
  std::filesystem::copy_file(jpeg, dir / "wrap.jpg");
  const auto file = write_triangle_gltf(dir, [](json& g) {
    g["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
    g["meshes"][0]["primitives"][0]["material"] = 0;
    g["textures"] = {{{"source", 0}}};
    g["images"] = {{{"uri", "wrap.jpg"}}};
  });
  const GltfAsset asset = load_gltf(file);
  ASSERT_EQ(asset.textures.size(), 1u);
  EXPECT_EQ(asset.textures[0].name, "wrap.jpg");
  EXPECT_EQ(asset.textures[0].width, 1024u);
  EXPECT_EQ(asset.textures[0].rgba8.size(), std::size_t(asset.textures[0].width) * asset.textures[0].height * 4);
  EXPECT_EQ(asset.textures[0].rgba8[3], 255);  // JPEG has no alpha: opaque
}

TEST(Gltf, PrimitiveModesBecomeTrianglesStrandsOrAreSkipped) {
  for (int i = 0; i <= 15; ++i) AVSM_REQUIRE_FILE(primitive_mode_model(i));
  const GltfAsset points = load_gltf(primitive_mode_model(0));
  EXPECT_EQ(points.point_primitives_skipped, 1u);
  EXPECT_TRUE(points.meshes.empty());

  // LINES without indices: 4 separate segments. With indices 0-3, 3-2, 2-1, 1-0:
  // consecutive segments share an index, so they join into one closed strand.
  const GltfAsset lines = load_gltf(primitive_mode_model(1));
  EXPECT_EQ(lines.line_strands.strand_count(), 4u);
  EXPECT_EQ(lines.line_strands.points.size(), 8u);
  const GltfAsset indexed_lines = load_gltf(primitive_mode_model(8));
  ASSERT_EQ(indexed_lines.line_strands.strand_count(), 1u);
  EXPECT_EQ(indexed_lines.line_strands.points.size(), 5u);
  EXPECT_EQ(indexed_lines.line_strands.points.front(), indexed_lines.line_strands.points.back());

  for (int model : {2, 3, 9, 10}) {  // LINE_LOOP and LINE_STRIP, plain and indexed: 5 points
    const GltfAsset asset = load_gltf(primitive_mode_model(model));
    ASSERT_EQ(asset.line_strands.strand_count(), 1u) << model;
    EXPECT_EQ(asset.line_strands.points.size(), 5u) << model;
    EXPECT_TRUE(asset.meshes.empty());
  }
  for (int model : {4, 5, 6, 11, 12, 13, 14, 15}) {  // strips, fans, lists; uint, ubyte, ushort indices
    const GltfAsset asset = load_gltf(primitive_mode_model(model));
    ASSERT_EQ(asset.meshes.size(), 1u) << model;
    EXPECT_EQ(asset.meshes[0].triangle_count(), 2u) << model;
    expect_unit_normals(asset);
    // The quad faces +Z: both triangles must agree (strip winding alternation handled).
    for (const glm::vec3& n : asset.meshes[0].normals) EXPECT_NEAR(n.z, 1.0f, 1e-5f) << model;
  }
}

TEST(Gltf, IndexComponentTypesGiveTheSameMesh) {
  for (int i : {13, 14, 15}) AVSM_REQUIRE_FILE(primitive_mode_model(i));
  const Mesh as_uint = load_gltf(primitive_mode_model(13)).meshes.at(0);
  const Mesh as_ubyte = load_gltf(primitive_mode_model(14)).meshes.at(0);
  const Mesh as_ushort = load_gltf(primitive_mode_model(15)).meshes.at(0);
  EXPECT_EQ(as_uint.positions, as_ubyte.positions);
  EXPECT_EQ(as_uint.positions, as_ushort.positions);
}

TEST(Gltf, MissingNormalsAreFlatBySpecOrSmoothOnRequest) {
  AVSM_REQUIRE_FILE(primitive_mode_model(13));
  const Mesh flat = load_gltf(primitive_mode_model(13)).meshes.at(0);
  EXPECT_EQ(flat.positions.size(), 6u);  // flat: every triangle its own corners
  GltfOptions smooth_options;
  smooth_options.missing_normals = NormalGeneration::smooth;
  const Mesh smooth = load_gltf(primitive_mode_model(13), smooth_options).meshes.at(0);
  EXPECT_EQ(smooth.positions.size(), 4u);
  for (const glm::vec3& n : smooth.normals) EXPECT_NEAR(glm::length(n), 1.0f, 1e-5f);
}

TEST(Gltf, ZeroNormalsAreRepairedWithAWarning) {
  const auto file = testing::assimp_model("glTF2/BoxBadNormals-glTF-Binary/BoxBadNormals.glb");
  AVSM_REQUIRE_FILE(file);
  const GltfAsset asset = load_gltf(file);
  expect_unit_normals(asset);
  ASSERT_FALSE(asset.warnings.empty());
  EXPECT_THAT(asset.warnings.back(), HasSubstr("zero-length normals replaced"));
}

TEST(Gltf, NodeHierarchyAndPlacementAreApplied) {
  TempDir dir;
  GltfOptions options;
  options.transform = glm::translate(glm::mat4(1.0f), glm::vec3(0, 0, 5));
  const GltfAsset asset = load_gltf(write_triangle_gltf(dir), options);
  ASSERT_EQ(asset.meshes.size(), 1u);
  const Mesh& mesh = asset.meshes[0];
  // placement (z + 5) * parent (x + 10) * child (y x 2); flat normals: 3 corners.
  EXPECT_EQ(mesh.positions[0], glm::vec3(10, 0, 5));
  EXPECT_EQ(mesh.positions[1], glm::vec3(11, 0, 5));
  EXPECT_EQ(mesh.positions[2], glm::vec3(10, 2, 5));
  EXPECT_NEAR(mesh.normals[0].z, 1.0f, 1e-6f);
  EXPECT_EQ(mesh.name, "tri");
  EXPECT_EQ(asset.materials.size(), 1u);  // the glTF default material
  EXPECT_EQ(asset.materials[0].name, "default");
}

TEST(Gltf, MirroringKeepsTrianglesCounterClockwise) {
  TempDir dir;
  const auto file = write_triangle_gltf(dir, [](json& g) { g["nodes"][1]["scale"] = {-1, 1, 1}; });
  const Mesh mesh = load_gltf(file).meshes.at(0);
  // Mirrored in x: the geometric normal of the (re-ordered) triangle must still be +Z.
  const glm::vec3 a = mesh.positions[mesh.indices[0]], b = mesh.positions[mesh.indices[1]], c = mesh.positions[mesh.indices[2]];
  EXPECT_GT(glm::cross(b - a, c - a).z, 0.0f);
  EXPECT_GT(mesh.normals[0].z, 0.0f);
}

// ---- bad input ----

TEST(GltfErrors, IndexOutOfRange) {
  for (const char* name : {"IndexOutOfRange.gltf", "AllIndicesOutOfRange.gltf"}) {
    const auto file = testing::assimp_model(std::string("glTF2/IndexOutOfRange/") + name);
    AVSM_REQUIRE_FILE(file);
    EXPECT_THAT(load_error_of([&] { load_gltf(file); }),
                AllOf(HasSubstr(name), HasSubstr("mesh 'Mesh' primitive 0: index "), HasSubstr("is out of range (24 vertices)")));
  }
}

TEST(GltfErrors, MissingBinaryBuffer) {
  const auto file = testing::assimp_model("glTF2/MissingBin/BoxTextured.gltf");
  AVSM_REQUIRE_FILE(file);
  EXPECT_THAT(load_error_of([&] { load_gltf(file); }),
              AllOf(HasSubstr("MissingBin/BoxTextured.gltf: invalid glTF"), HasSubstr("BoxTextured0.bin")));
}

TEST(GltfErrors, NodeCycle) {
  const auto file = testing::assimp_model("glTF2/RecursiveNodes/RecursiveNodes.gltf");
  AVSM_REQUIRE_FILE(file);
  EXPECT_THAT(load_error_of([&] { load_gltf(file); }), HasSubstr("RecursiveNodes.gltf: scene lists node 0, which is not a root"));
}

TEST(GltfErrors, InfinitePositions) {
  const auto file = testing::assimp_model("glTF2/BoxWithInfinites-glTF-Binary/BoxWithInfinites.glb");
  AVSM_REQUIRE_FILE(file);
  EXPECT_THAT(load_error_of([&] { load_gltf(file); }), HasSubstr("BoxWithInfinites.glb: mesh 'Mesh' primitive 0: position 0 is not finite"));
}

// tinygltf ignores members of the wrong type; we refuse them with the JSON path.
TEST(GltfErrors, WrongJsonTypes) {
  const std::pair<const char*, const char*> cases[] = {
      {"badArray.gltf", "invalid glTF: meshes[0].primitives: expected an array"},
      {"badNumber.gltf", "invalid glTF: materials[0].normalTexture.scale: expected a number"},
      {"badObject.gltf", "invalid glTF: materials[0].pbrMetallicRoughness: expected an object"},
      {"badString.gltf", "invalid glTF: scenes[0].name: expected a string"},
      {"badUint.gltf", "invalid glTF: materials[0].pbrMetallicRoughness.baseColorTexture.index: expected an index"},
      {"badExtension.gltf", "baseColorTexture.extensions.KHR_texture_transform: expected an object"},
  };
  for (const auto& [name, message] : cases) {
    const auto file = testing::assimp_model(std::string("glTF2/wrongTypes/") + name);
    AVSM_REQUIRE_FILE(file);
    EXPECT_THAT(load_error_of([&] { load_gltf(file); }), AllOf(HasSubstr(std::string(name) + ": "), HasSubstr(message))) << name;
  }
}

TEST(GltfErrors, IncorrectVertexArrays) {
  const auto file = testing::assimp_model("glTF2/IncorrectVertexArrays/Cube.gltf");
  AVSM_REQUIRE_FILE(file);
  EXPECT_THAT(load_error_of([&] { load_gltf(file); }),
              HasSubstr("Cube.gltf: mesh 'TruncatedCube' primitive 0: 35 indices is not a whole number of triangles"));
  // (meshes are reached in node order; TruncatedCube's node comes first)
}

TEST(GltfErrors, TruncatedAndWrongMagicGlb) {
  const auto file = testing::shared_content("cornell_box/CornellBox.glb");
  AVSM_REQUIRE_FILE(file);
  TempDir dir;
  auto bytes = testing::read_bytes(file);
  testing::write_bytes(dir / "half.glb", {bytes.begin(), bytes.begin() + bytes.size() / 2});
  EXPECT_THAT(load_error_of([&] { load_gltf(dir / "half.glb"); }), HasSubstr("half.glb: invalid glTF"));
  bytes[0] = std::byte{'X'};
  testing::write_bytes(dir / "magic.glb", bytes);
  EXPECT_THAT(load_error_of([&] { load_gltf(dir / "magic.glb"); }), HasSubstr("magic.glb: not a GLB file: no 'glTF' magic"));
}

TEST(GltfErrors, NanPosition) {
  TempDir dir;
  const auto file = write_triangle_gltf(dir, {}, {0, 0, 0, std::numeric_limits<float>::quiet_NaN(), 0, 0, 0, 1, 0});
  EXPECT_THAT(load_error_of([&] { load_gltf(file); }), HasSubstr("tri.gltf: mesh 'tri' primitive 0: position 1 is not finite"));
}

TEST(GltfErrors, AccessorOutsideItsBufferView) {
  TempDir dir;
  const auto file = write_triangle_gltf(dir, [](json& g) { g["accessors"][0]["count"] = 4; });
  EXPECT_THAT(load_error_of([&] { load_gltf(file); }),
              HasSubstr("mesh 'tri' primitive 0 POSITION (accessor 0): 4 elements do not fit in bufferView 0 (36 bytes)"));
}

TEST(GltfErrors, UnsupportedRequiredExtension) {
  TempDir dir;
  const auto file = write_triangle_gltf(dir, [](json& g) {
    g["extensionsUsed"] = {"KHR_draco_mesh_compression"};
    g["extensionsRequired"] = {"KHR_draco_mesh_compression"};
  });
  EXPECT_THAT(load_error_of([&] { load_gltf(file); }), HasSubstr("requires extension KHR_draco_mesh_compression"));
}

// A GLB the fuzz target found (a buffer declared empty, views reaching into it) on
// which tinygltf throws std::out_of_range: a LoadError naming the file, never a crash.
TEST(GltfErrors, WhatTinygltfThrowsOnIsALoadError) {
  const std::filesystem::path file = std::filesystem::path(AVSM_SCENE_TEST_DATA_DIR) / "tinygltf_throws.glb";
  EXPECT_THAT(load_error_of([&] { load_gltf(file); }),
              AllOf(HasSubstr("tinygltf_throws.glb: invalid glTF: tinygltf failed reading it")));
}

TEST(GltfErrors, MissingOrUndecodableTexture) {
  TempDir dir;
  auto with_texture = [](const std::string& uri) {
    return [uri](json& g) {
      g["materials"] = {{{"pbrMetallicRoughness", {{"baseColorTexture", {{"index", 0}}}}}}};
      g["meshes"][0]["primitives"][0]["material"] = 0;
      g["textures"] = {{{"source", 0}}};
      g["images"] = {{{"uri", uri}}};
    };
  };
  EXPECT_THAT(load_error_of([&] { load_gltf(write_triangle_gltf(dir, with_texture("absent.png"))); }),
              HasSubstr("image 0 'absent.png' has no data"));
  testing::write_text(dir / "garbage.png", "this is not a PNG");
  EXPECT_THAT(load_error_of([&] { load_gltf(write_triangle_gltf(dir, with_texture("garbage.png"))); }),
              HasSubstr("image 0 'garbage.png' cannot be decoded"));
}

TEST(GltfErrors, MissingFileAndNoExternalFilesWhenForbidden) {
  TempDir dir;
  EXPECT_THAT(load_error_of([&] { load_gltf(dir / "absent.glb"); }), HasSubstr("absent.glb: file not found"));
  GltfOptions sandboxed;
  sandboxed.allow_external_files = false;
  EXPECT_THAT(load_error_of([&] { load_gltf(write_triangle_gltf(dir), sandboxed); }), HasSubstr("tri.gltf: invalid glTF"));
}

TEST(GltfErrors, InstancingBeyondTheVertexBudget) {
  TempDir dir;
  const auto file = write_triangle_gltf(dir, [](json& g) {
    for (int i = 0; i < 50; ++i) {
      g["nodes"].push_back({{"mesh", 0}});
      g["scenes"][0]["nodes"].push_back(g["nodes"].size() - 1);
    }
  });
  GltfOptions options;
  options.max_vertices = 100;
  EXPECT_THAT(load_error_of([&] { load_gltf(file, options); }), HasSubstr("more than 100 vertices in total"));
}

}  // namespace
}  // namespace gltf_test
}  // namespace avsm::scene
