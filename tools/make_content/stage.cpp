// Procedural glTF stage: floor, box, sphere, and the stand that holds the hair rod.
#include "content.h"

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <cmath>
#include <cstring>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace avsm::content {
namespace {

using json = nlohmann::ordered_json;
constexpr float kPi = 3.14159265358979f;

struct MeshData {
  std::string name;
  std::vector<glm::vec3> positions, normals;
  std::vector<glm::vec2> uvs;
  std::vector<std::uint16_t> indices;
  int material = 0;

  void quad(std::uint16_t a, std::uint16_t b, std::uint16_t c, std::uint16_t d) {
    indices.insert(indices.end(), {a, b, c, a, c, d});
  }
};

// For convex shapes around the origin: make every triangle counter-clockwise
// seen from outside, whatever order the generator produced.
void orient_outward(MeshData& mesh) {
  for (std::size_t t = 0; t < mesh.indices.size(); t += 3) {
    const glm::vec3 a = mesh.positions[mesh.indices[t]], b = mesh.positions[mesh.indices[t + 1]],
                    c = mesh.positions[mesh.indices[t + 2]];
    if (glm::dot(glm::cross(b - a, c - a), a + b + c) < 0.0f) std::swap(mesh.indices[t + 1], mesh.indices[t + 2]);
  }
}

MeshData make_floor(float half_size) {
  MeshData mesh{"floor"};
  const float s = half_size;
  mesh.positions = {{-s, 0, -s}, {-s, 0, s}, {s, 0, s}, {s, 0, -s}};
  mesh.normals.assign(4, {0, 1, 0});
  mesh.uvs = {{0, 0}, {0, 4}, {4, 4}, {4, 0}};
  mesh.quad(0, 1, 2, 3);
  return mesh;
}

MeshData make_unit_cube() {
  MeshData mesh{"box"};
  for (int axis = 0; axis < 3; ++axis)
    for (float sign : {-1.0f, 1.0f}) {
      glm::vec3 n(0.0f), u(0.0f), v(0.0f);
      n[axis] = sign;
      u[(axis + 1) % 3] = 1.0f;
      v[(axis + 2) % 3] = 1.0f;
      const auto base = std::uint16_t(mesh.positions.size());
      for (glm::vec2 corner : {glm::vec2(-1, -1), glm::vec2(1, -1), glm::vec2(1, 1), glm::vec2(-1, 1)}) {
        mesh.positions.push_back(0.5f * (n + corner.x * u + corner.y * v));
        mesh.normals.push_back(n);
        mesh.uvs.push_back(0.5f * (corner + 1.0f));
      }
      mesh.quad(base, base + 1, base + 2, base + 3);
    }
  orient_outward(mesh);
  return mesh;
}

MeshData make_unit_sphere(int stacks, int slices) {
  MeshData mesh{"sphere"};
  for (int i = 0; i <= stacks; ++i)
    for (int j = 0; j <= slices; ++j) {
      const float theta = kPi * i / stacks, phi = 2.0f * kPi * j / slices;
      const glm::vec3 p(std::sin(theta) * std::cos(phi), std::cos(theta), std::sin(theta) * std::sin(phi));
      mesh.positions.push_back(p);
      mesh.normals.push_back(p);
      mesh.uvs.emplace_back(float(j) / slices, float(i) / stacks);
    }
  for (int i = 0; i < stacks; ++i)
    for (int j = 0; j < slices; ++j) {
      const auto at = [&](int a, int b) { return std::uint16_t(a * (slices + 1) + b); };
      if (i > 0) mesh.indices.insert(mesh.indices.end(), {at(i, j), at(i + 1, j), at(i, j + 1)});
      if (i + 1 < stacks) mesh.indices.insert(mesh.indices.end(), {at(i, j + 1), at(i + 1, j), at(i + 1, j + 1)});
    }
  orient_outward(mesh);
  return mesh;
}

// Radius 1, from y = -0.5 to 0.5, with flat caps.
MeshData make_unit_cylinder(int segments) {
  MeshData mesh{"cylinder"};
  for (int s = 0; s <= segments; ++s) {
    const float phi = 2.0f * kPi * s / segments;
    const glm::vec3 n(std::cos(phi), 0.0f, std::sin(phi));
    for (float y : {-0.5f, 0.5f}) {
      mesh.positions.emplace_back(n.x, y, n.z);
      mesh.normals.push_back(n);
      mesh.uvs.emplace_back(float(s) / segments, y + 0.5f);
    }
  }
  for (int s = 0; s < segments; ++s) {
    const auto a = std::uint16_t(2 * s);
    mesh.quad(a, a + 1, a + 3, a + 2);
  }
  for (float y : {-0.5f, 0.5f}) {
    const auto center = std::uint16_t(mesh.positions.size());
    mesh.positions.emplace_back(0.0f, y, 0.0f);
    mesh.normals.emplace_back(0.0f, y > 0 ? 1.0f : -1.0f, 0.0f);
    mesh.uvs.emplace_back(0.5f, 0.5f);
    for (int s = 0; s <= segments; ++s) {
      const float phi = 2.0f * kPi * s / segments;
      mesh.positions.emplace_back(std::cos(phi), y, std::sin(phi));
      mesh.normals.push_back(mesh.normals[center]);
      mesh.uvs.emplace_back(0.5f + 0.5f * std::cos(phi), 0.5f + 0.5f * std::sin(phi));
    }
    for (int s = 0; s < segments; ++s)
      mesh.indices.insert(mesh.indices.end(), {center, std::uint16_t(center + 1 + s), std::uint16_t(center + 2 + s)});
  }
  orient_outward(mesh);
  return mesh;
}

class GltfWriter {
 public:
  int add_material(const std::string& name, glm::vec3 color, bool double_sided) {
    json material = {{"name", name},
                     {"pbrMetallicRoughness",
                      {{"baseColorFactor", {color.r, color.g, color.b, 1.0f}}, {"metallicFactor", 0.0f}, {"roughnessFactor", 0.7f}}}};
    if (double_sided) material["doubleSided"] = true;
    materials_.push_back(material);
    return int(materials_.size() - 1);
  }

  int add_mesh(const MeshData& mesh) {
    glm::vec3 lo(1e30f), hi(-1e30f);
    for (const glm::vec3& p : mesh.positions) lo = glm::min(lo, p), hi = glm::max(hi, p);
    const int count = int(mesh.positions.size());
    json attributes = {
        {"POSITION", add_accessor(add_view(mesh.positions, 34962), 5126, count, "VEC3", json{lo.x, lo.y, lo.z}, json{hi.x, hi.y, hi.z})},
        {"NORMAL", add_accessor(add_view(mesh.normals, 34962), 5126, count, "VEC3")},
        {"TEXCOORD_0", add_accessor(add_view(mesh.uvs, 34962), 5126, count, "VEC2")}};
    const int indices = add_accessor(add_view(mesh.indices, 34963), 5123, int(mesh.indices.size()), "SCALAR");
    meshes_.push_back({{"name", mesh.name},
                       {"primitives", json::array({{{"attributes", attributes}, {"indices", indices}, {"material", mesh.material}}})}});
    return int(meshes_.size() - 1);
  }

  int add_node(json node) {
    nodes_.push_back(std::move(node));
    return int(nodes_.size() - 1);
  }

  void write(const std::filesystem::path& gltf_file, const std::filesystem::path& bin_file,
             const std::vector<int>& roots) const {
    const json gltf = {
        {"asset", {{"version", "2.0"}, {"generator", "avsm-make-content"}}},
        {"scene", 0},
        {"scenes", json::array({{{"name", "stage"}, {"nodes", roots}}})},
        {"nodes", nodes_},
        {"meshes", meshes_},
        {"materials", materials_},
        {"accessors", accessors_},
        {"bufferViews", views_},
        {"buffers", json::array({{{"uri", bin_file.filename().string()}, {"byteLength", buffer_.size()}}})}};
    std::ofstream text(gltf_file);
    text << gltf.dump(1) << "\n";
    std::ofstream binary(bin_file, std::ios::binary);
    binary.write(reinterpret_cast<const char*>(buffer_.data()), std::streamsize(buffer_.size()));
    if (!text || !binary) throw std::runtime_error(gltf_file.string() + ": cannot write");
  }

 private:
  template <class T>
  int add_view(const std::vector<T>& values, int target) {
    while (buffer_.size() % 4 != 0) buffer_.push_back(0);  // accessors need aligned components
    const std::size_t offset = buffer_.size(), length = values.size() * sizeof(T);
    buffer_.resize(offset + length);
    std::memcpy(buffer_.data() + offset, values.data(), length);
    views_.push_back({{"buffer", 0}, {"byteOffset", offset}, {"byteLength", length}, {"target", target}});
    return int(views_.size() - 1);
  }

  int add_accessor(int view, int component_type, int count, const char* type, json min = nullptr, json max = nullptr) {
    json accessor = {{"bufferView", view}, {"componentType", component_type}, {"count", count}, {"type", type}};
    if (!min.is_null()) accessor["min"] = min, accessor["max"] = max;
    accessors_.push_back(std::move(accessor));
    return int(accessors_.size() - 1);
  }

  json nodes_ = json::array(), meshes_ = json::array(), materials_ = json::array(), accessors_ = json::array(),
       views_ = json::array();
  std::vector<std::uint8_t> buffer_;
};

json rotation_about(glm::dvec3 axis, double degrees) {
  const double half = 0.5 * degrees * 3.14159265358979323846 / 180.0;
  return {axis.x * std::sin(half), axis.y * std::sin(half), axis.z * std::sin(half), std::cos(half)};
}

}  // namespace

void write_stage_gltf(const std::filesystem::path& gltf_file, const std::filesystem::path& bin_file) {
  GltfWriter writer;
  MeshData floor = make_floor(4.0), box = make_unit_cube(), sphere = make_unit_sphere(16, 32),
           cylinder = make_unit_cylinder(24);
  floor.material = writer.add_material("floor", {0.55, 0.55, 0.55}, true);
  box.material = writer.add_material("terracotta", {0.72, 0.32, 0.2}, false);
  sphere.material = writer.add_material("chalk", {0.85, 0.85, 0.82}, false);
  cylinder.material = writer.add_material("dark_metal", {0.3, 0.3, 0.32}, false);
  const int floor_mesh = writer.add_mesh(floor), box_mesh = writer.add_mesh(box),
            sphere_mesh = writer.add_mesh(sphere), cylinder_mesh = writer.add_mesh(cylinder);

  std::vector<int> roots;
  roots.push_back(writer.add_node({{"name", "floor"}, {"mesh", floor_mesh}}));
  roots.push_back(writer.add_node({{"name", "box"}, {"mesh", box_mesh}, {"translation", {1.9, 0.3, 1.1}},
                                   {"rotation", rotation_about({0, 1, 0}, 25.0)}, {"scale", {0.6, 0.6, 0.6}}}));
  roots.push_back(writer.add_node({{"name", "sphere"}, {"mesh", sphere_mesh}, {"translation", {-0.2, 0.35, 1.4}},
                                   {"scale", {0.35, 0.35, 0.35}}}));
  // The stand: a parent node placing the rod and two posts (exercises the hierarchy).
  // The rod (1.3 m long, 2 cm radius) is the cylinder's Y axis turned onto X.
  const int rod = writer.add_node({{"name", "rod"}, {"mesh", cylinder_mesh}, {"translation", {0.0, 1.9, 0.0}},
                                   {"rotation", rotation_about({0, 0, 1}, 90.0)}, {"scale", {0.02, 1.3, 0.02}}});
  const int left = writer.add_node({{"name", "post_left"}, {"mesh", cylinder_mesh}, {"translation", {-0.65, 0.95, 0.0}},
                                    {"scale", {0.025, 1.9, 0.025}}});
  const int right = writer.add_node({{"name", "post_right"}, {"mesh", cylinder_mesh}, {"translation", {0.65, 0.95, 0.0}},
                                     {"scale", {0.025, 1.9, 0.025}}});
  roots.push_back(writer.add_node({{"name", "stand"}, {"translation", {1.0, 0.0, -0.3}}, {"children", {rod, left, right}}}));
  writer.write(gltf_file, bin_file, roots);
}

// Written as text rather than built with nlohmann::json so that it reads like
// the hand-written scenes in content/examples (and numbers stay short).
void write_scene_json(const std::filesystem::path& file) {
  static const char* const kScene = R"({
  "version": 1,
  "description": "Default scene, generated by avsm-make-content: a smoke plume (OpenVDB), a hair curtain (cyHair) hanging from a rod, a glTF stage, a sun and a spot light, one camera. Units: metres, +Y up. The lights' maps are paged (docs/shadows.md): 32^2 pages in pools sized for what each light asks for at 1280x720; 'resolution' is their dense maps' size (--shadow-layout dense) and the coarsest level their receivers fall back to.",
  "models": [
    { "name": "stage", "file": "stage.gltf" }
  ],
  "volumes": [
    {
      "name": "plume", "file": "plume.vdb", "grid": "density",
      "transform": { "translation": [-1.3, 0.0, -0.4] },
      "extinction_scale": 1.5,
      "albedo": [0.9, 0.9, 0.9]
    }
  ],
  "hair": [
    {
      "name": "curtain", "file": "curtain.hair",
      "transform": { "translation": [1.0, 1.9, -0.3] }
    }
  ],
  "lights": [
    {
      "name": "sun", "type": "directional",
      "direction": [0.35, -1.0, 0.25],
      "color": [1.0, 0.96, 0.9], "intensity": 3.0,
      "shadow": { "technique": "avsm", "nodes": 8, "layout": "paged", "fit": "scene", "filter": "trilinear", "sort": true,
                  "page_size": 32, "page_pool_mib": 66, "page_builds_per_frame": 32, "resolution": 256 }
    },
    {
      "name": "key_spot", "type": "spot",
      "position": [3.0, 3.6, 2.4], "target": [0.2, 0.9, -0.2],
      "inner_cone_deg": 24.0, "outer_cone_deg": 32.0,
      "color": [1.0, 0.9, 0.8], "intensity": 40.0,
      "shadow": { "technique": "avsm", "nodes": 8, "layout": "paged", "filter": "trilinear", "sort": true,
                  "page_size": 32, "page_pool_mib": 46, "page_builds_per_frame": 32, "resolution": 256 }
    }
  ],
  "cameras": [
    {
      "name": "main",
      "position": [0.2, 1.7, 5.8], "target": [0.1, 1.1, 0.0], "up": [0.0, 1.0, 0.0],
      "vertical_fov_deg": 45.0, "near": 0.05, "far": 60.0
    }
  ]
}
)";
  std::ofstream stream(file);
  stream << kScene;
  if (!stream) throw std::runtime_error(file.string() + ": cannot write");
}

}  // namespace avsm::content
