#include "scene/gltf_json_check.h"

#include "scene/load_error.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <cstring>
#include <string>
#include <string_view>

namespace avsm::scene::detail {
namespace {

using json = nlohmann::json;

class Checker {
 public:
  explicit Checker(const std::filesystem::path& file) : file_(file) {}

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw LoadError(file_, "invalid glTF: " + (path.empty() ? std::string("top level") : path) + ": " + problem);
  }

  // Each checks member `key` of `object` if present.
  void index(const json& object, const std::string& path, const char* key) const {
    if (const json* v = find(object, key); v && !(v->is_number_unsigned() || (v->is_number_integer() && v->get<std::int64_t>() >= 0)))
      fail(path + "." + key, "expected an index (integer >= 0)");
  }
  void number(const json& object, const std::string& path, const char* key) const {
    if (const json* v = find(object, key); v && !v->is_number()) fail(path + "." + key, "expected a number");
  }
  void boolean(const json& object, const std::string& path, const char* key) const {
    if (const json* v = find(object, key); v && !v->is_boolean()) fail(path + "." + key, "expected true or false");
  }
  void string(const json& object, const std::string& path, const char* key) const {
    if (const json* v = find(object, key); v && !v->is_string()) fail(path + "." + key, "expected a string");
  }
  void numbers(const json& object, const std::string& path, const char* key, std::size_t count) const {
    const json* v = find(object, key);
    if (!v) return;
    if (!v->is_array() || v->size() != count) fail(path + "." + key, "expected an array of " + std::to_string(count) + " numbers");
    for (const json& element : *v)
      if (!element.is_number()) fail(path + "." + key, "expected an array of " + std::to_string(count) + " numbers");
  }
  void indices(const json& object, const std::string& path, const char* key) const {
    const json* v = find(object, key);
    if (!v) return;
    if (!v->is_array()) fail(path + "." + key, "expected an array of indices");
    for (std::size_t i = 0; i < v->size(); ++i) index_value((*v)[i], path + "." + key + "[" + std::to_string(i) + "]");
  }
  void extensions(const json& object, const std::string& path) const {
    const json* v = find(object, "extensions");
    if (!v) return;
    if (!v->is_object()) fail(path + ".extensions", "expected an object");
    for (const auto& [name, extension] : v->items())
      if (!extension.is_object()) fail(path + ".extensions." + name, "expected an object");
  }
  // Calls check(element, path) for each object in the array `key`.
  template <class Check>
  void objects(const json& object, const std::string& path, const char* key, Check check) const {
    const json* v = find(object, key);
    if (!v) return;
    const std::string array_path = path.empty() ? key : path + "." + key;
    if (!v->is_array()) fail(array_path, "expected an array");
    for (std::size_t i = 0; i < v->size(); ++i) {
      const std::string element_path = array_path + "[" + std::to_string(i) + "]";
      if (!(*v)[i].is_object()) fail(element_path, "expected an object");
      check((*v)[i], element_path);
    }
  }
  template <class Check>
  void object(const json& parent, const std::string& path, const char* key, Check check) const {
    const json* v = find(parent, key);
    if (!v) return;
    if (!v->is_object()) fail(path + "." + key, "expected an object");
    check(*v, path + "." + key);
  }

 private:
  static const json* find(const json& object, const char* key) {
    const auto found = object.find(key);
    return found == object.end() ? nullptr : &*found;
  }
  void index_value(const json& v, const std::string& path) const {
    if (!(v.is_number_unsigned() || (v.is_number_integer() && v.get<std::int64_t>() >= 0)))
      fail(path, "expected an index (integer >= 0)");
  }
  const std::filesystem::path& file_;
};

void check_texture_info(const Checker& c, const json& info, const std::string& path) {
  c.number(info, path, "scale");     // normalTexture
  c.number(info, path, "strength");  // occlusionTexture
  if (!info.contains("index")) c.fail(path + ".index", "required");
  c.index(info, path, "index");
  c.index(info, path, "texCoord");
  c.extensions(info, path);
}

void check_material(const Checker& c, const json& material, const std::string& path) {
  c.string(material, path, "name");
  c.object(material, path, "pbrMetallicRoughness", [&](const json& pbr, const std::string& pbr_path) {
    c.numbers(pbr, pbr_path, "baseColorFactor", 4);
    c.object(pbr, pbr_path, "baseColorTexture", [&](const json& t, const std::string& p) { check_texture_info(c, t, p); });
    c.number(pbr, pbr_path, "metallicFactor");
    c.number(pbr, pbr_path, "roughnessFactor");
  });
  for (const char* texture : {"normalTexture", "occlusionTexture", "emissiveTexture"})
    c.object(material, path, texture, [&](const json& t, const std::string& p) { check_texture_info(c, t, p); });
  c.numbers(material, path, "emissiveFactor", 3);
  c.string(material, path, "alphaMode");
  c.number(material, path, "alphaCutoff");
  c.boolean(material, path, "doubleSided");
  c.extensions(material, path);
}

void check_mesh(const Checker& c, const json& mesh, const std::string& path) {
  c.string(mesh, path, "name");
  if (!mesh.contains("primitives")) c.fail(path + ".primitives", "required");
  c.objects(mesh, path, "primitives", [&](const json& primitive, const std::string& p) {
    if (!primitive.contains("attributes")) c.fail(p + ".attributes", "required");
    c.object(primitive, p, "attributes", [&](const json& attributes, const std::string& a) {
      for (const auto& [name, unused] : attributes.items()) c.index(attributes, a, name.c_str());
    });
    c.index(primitive, p, "indices");
    c.index(primitive, p, "material");
    c.index(primitive, p, "mode");
    c.extensions(primitive, p);
  });
}

void check_node(const Checker& c, const json& node, const std::string& path) {
  c.string(node, path, "name");
  c.index(node, path, "mesh");
  c.indices(node, path, "children");
  c.numbers(node, path, "matrix", 16);
  c.numbers(node, path, "translation", 3);
  c.numbers(node, path, "rotation", 4);
  c.numbers(node, path, "scale", 3);
  c.extensions(node, path);
}

void check_document(const Checker& c, const json& root) {
  if (!root.is_object()) c.fail("", "expected an object");
  c.index(root, "", "scene");
  c.objects(root, "", "scenes", [&](const json& scene, const std::string& p) {
    c.string(scene, p, "name");
    c.indices(scene, p, "nodes");
  });
  c.objects(root, "", "nodes", [&](const json& node, const std::string& p) { check_node(c, node, p); });
  c.objects(root, "", "meshes", [&](const json& mesh, const std::string& p) { check_mesh(c, mesh, p); });
  c.objects(root, "", "materials", [&](const json& material, const std::string& p) { check_material(c, material, p); });
  c.objects(root, "", "textures", [&](const json& texture, const std::string& p) {
    c.index(texture, p, "source");
    c.index(texture, p, "sampler");
  });
  c.objects(root, "", "images", [&](const json& image, const std::string& p) {
    c.string(image, p, "uri");
    c.index(image, p, "bufferView");
    c.string(image, p, "mimeType");
  });
  c.objects(root, "", "accessors", [&](const json& accessor, const std::string& p) {
    for (const char* key : {"bufferView", "byteOffset", "componentType", "count"}) c.index(accessor, p, key);
    c.string(accessor, p, "type");
    c.boolean(accessor, p, "normalized");
  });
  c.objects(root, "", "bufferViews", [&](const json& view, const std::string& p) {
    for (const char* key : {"buffer", "byteOffset", "byteLength", "byteStride"}) c.index(view, p, key);
  });
  c.objects(root, "", "buffers", [&](const json& buffer, const std::string& p) {
    c.string(buffer, p, "uri");
    c.index(buffer, p, "byteLength");
  });
  for (const char* key : {"extensionsUsed", "extensionsRequired"})
    if (root.contains(key) && (!root[key].is_array() || !std::all_of(root[key].begin(), root[key].end(), [](const json& v) { return v.is_string(); })))
      c.fail(key, "expected an array of strings");
  c.extensions(root, "");
}

// The JSON text of a .gltf, or of a .glb's first chunk; empty if the GLB
// framing is broken (tinygltf will say how).
std::string_view json_text(std::span<const std::byte> bytes) {
  const char* data = reinterpret_cast<const char*>(bytes.data());
  if (bytes.size() < 4 || std::memcmp(data, "glTF", 4) != 0) return {data, bytes.size()};
  if (bytes.size() < 20) return {};
  std::uint32_t chunk_length = 0;
  std::memcpy(&chunk_length, data + 12, 4);
  if (std::memcmp(data + 16, "JSON", 4) != 0 || chunk_length > bytes.size() - 20) return {};
  return {data + 20, chunk_length};
}

}  // namespace

void check_gltf_json_types(std::span<const std::byte> bytes, const std::filesystem::path& file) {
  const std::string_view text = json_text(bytes);
  if (text.empty()) return;
  const json root = json::parse(text.begin(), text.end(), nullptr, /*allow_exceptions=*/false);
  if (root.is_discarded()) return;  // not JSON: tinygltf reports the syntax error
  check_document(Checker(file), root);
}

}  // namespace avsm::scene::detail
