// glTF loading: tinygltf parses (Debian's shared libtinygltf), this file
// validates everything it hands us before touching buffer bytes. Images are
// decoded by image_decode.cpp, not by tinygltf.
#include "scene/gltf.h"

#include "scene/binary_reader.h"
#include "scene/gltf_extensions.h"
#include "scene/gltf_json_check.h"
#include "scene/image_decode.h"
#include "scene/load_error.h"

#include <tiny_gltf.h>

#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cmath>
#include <cstring>
#include <limits>
#include <map>
#include <numeric>
#include <optional>
#include <set>
#include <tuple>

namespace avsm::scene {
namespace {

// ---- file access handed to tinygltf: bounded, regular files only, optional ----

bool file_exists(const std::string& path, void* user) {
  const auto* options = static_cast<const GltfOptions*>(user);
  std::error_code error;
  return options->allow_external_files && std::filesystem::is_regular_file(path, error);
}

std::string expand_path(const std::string& path, void*) { return path; }

bool read_whole_file(std::vector<unsigned char>* out, std::string* err, const std::string& path, void* user) {
  const auto* options = static_cast<const GltfOptions*>(user);
  if (!options->allow_external_files) {
    if (err) *err += "external file '" + path + "' not allowed here\n";
    return false;
  }
  try {
    const auto bytes = detail::read_file_bytes(path, options->max_file_bytes);
    const auto* begin = reinterpret_cast<const unsigned char*>(bytes.data());
    out->assign(begin, begin + bytes.size());
    return true;
  } catch (const LoadError& error) {
    if (err) *err += std::string(error.what()) + "\n";
    return false;
  }
}

bool refuse_write(std::string* err, const std::string&, const std::vector<unsigned char>&, void*) {
  if (err) *err += "writing is not supported\n";
  return false;
}

// Images are kept encoded: only base-colour textures get decoded, and only
// after their size has been checked (see decode_texture).
bool keep_encoded_image(tinygltf::Image* image, const int, std::string*, std::string*, int, int,
                        const unsigned char* bytes, int size, void*) {
  image->as_is = true;
  if (bytes != nullptr && size > 0) image->image.assign(bytes, bytes + size);
  return true;
}

std::string trim(std::string text) {
  while (!text.empty() && std::isspace(static_cast<unsigned char>(text.back()))) text.pop_back();
  std::replace(text.begin(), text.end(), '\n', ';');
  return text;
}

tinygltf::Model parse_model(std::span<const std::byte> bytes, const std::filesystem::path& name,
                            const GltfOptions& options, std::string& warning) {
  const bool has_glb_magic = bytes.size() >= 4 && std::memcmp(bytes.data(), "glTF", 4) == 0;
  if (name.extension() == ".glb" && !has_glb_magic) throw LoadError(name, "not a GLB file: no 'glTF' magic");
  if (bytes.size() > std::numeric_limits<unsigned int>::max()) throw LoadError(name, "file is too large");

  detail::check_gltf_json_types(bytes, name);

  tinygltf::TinyGLTF loader;
  loader.SetFsCallbacks(tinygltf::FsCallbacks{&file_exists, &expand_path, &read_whole_file, &refuse_write,
                                              const_cast<GltfOptions*>(&options)});
  loader.SetImageLoader(&keep_encoded_image, nullptr);
  tinygltf::Model model;
  std::string error;
  const std::string base_dir = name.parent_path().string();
  const auto* data = reinterpret_cast<const unsigned char*>(bytes.data());
  bool ok = false;
  try {
    ok = has_glb_magic ? loader.LoadBinaryFromMemory(&model, &error, &warning, data,
                                                     static_cast<unsigned int>(bytes.size()), base_dir)
                       : loader.LoadASCIIFromString(&model, &error, &warning, reinterpret_cast<const char*>(data),
                                                    static_cast<unsigned int>(bytes.size()), base_dir);
  } catch (const std::exception& e) {
    // tinygltf indexes some arrays with .at() before checking them (a GLB whose buffer
    // is declared empty, found by the fuzz target): a malformed file, not a crash.
    throw LoadError(name, std::string("invalid glTF: tinygltf failed reading it (") + e.what() + ")");
  }
  if (!ok) throw LoadError(name, "invalid glTF: " + (error.empty() ? std::string("tinygltf refused it") : trim(error)));
  return model;
}

// ---- accessors ----

int component_bytes(int component_type) {
  switch (component_type) {
    case TINYGLTF_COMPONENT_TYPE_BYTE:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return 1;
    case TINYGLTF_COMPONENT_TYPE_SHORT:
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: return 2;
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT:
    case TINYGLTF_COMPONENT_TYPE_FLOAT: return 4;
    default: return 0;
  }
}

int component_count(int type) {
  switch (type) {
    case TINYGLTF_TYPE_SCALAR: return 1;
    case TINYGLTF_TYPE_VEC2: return 2;
    case TINYGLTF_TYPE_VEC3: return 3;
    case TINYGLTF_TYPE_VEC4: return 4;
    default: return 0;
  }
}

// Validated view of an accessor's bytes; data == nullptr means "all zeros"
// (an accessor without a bufferView, as the spec allows).
struct AccessorView {
  const unsigned char* data = nullptr;
  std::size_t stride = 0;
  std::size_t count = 0;
  int component_type = 0;
  int components = 0;
  bool normalized = false;
};

class Loader {
 public:
  Loader(const tinygltf::Model& model, const std::filesystem::path& file, const GltfOptions& options)
      : model_(model), file_(file), options_(options) {}

  GltfAsset load();

 private:
  [[noreturn]] void fail(const std::string& problem) const { throw LoadError(file_, problem); }

  AccessorView view(int accessor_index, const std::string& what) const;
  // Which integer component types an attribute may have besides float: glTF's base
  // specification allows normalized unsigned bytes and shorts for UVs; KHR_mesh_quantization
  // allows every byte and short type for positions, normals, tangents and UVs.
  enum class Integers { none, normalized_unsigned, any };
  template <int N>
  std::vector<glm::vec<N, float>> read_vectors(int accessor_index, const std::string& what, Integers allowed) const;
  Integers quantized_or(Integers base) const { return quantized_ ? Integers::any : base; }
  std::vector<std::uint32_t> read_indices(int accessor_index, const std::string& what) const;

  void check_required_extensions() const;
  std::vector<int> root_nodes() const;
  void visit_nodes();
  void read_node_animation();
  template <int N>
  Track<N> read_channel(const tinygltf::Animation& animation, const tinygltf::AnimationChannel& channel, const std::string& what) const;
  void add_mesh_instance(int mesh_index, const std::string& node_name, const glm::mat4& world);
  void count_vertices(std::size_t count, const std::string& name);
  void repair_zero_normals(Mesh& mesh, const std::string& name);
  void finish_tangents(Mesh& mesh, const std::string& name);
  void add_triangles(const tinygltf::Primitive& primitive, const std::string& name,
                     std::vector<std::uint32_t> indices, const glm::mat4& world);
  void add_lines(const tinygltf::Primitive& primitive, const std::string& name, int mode, const std::vector<std::uint32_t>& indices,
                 const std::vector<glm::vec3>& positions);
  std::uint32_t material_index(int gltf_material);
  Material convert_material(const tinygltf::Material& source);
  void convert_textures(const tinygltf::Material& source, const std::string& label, Material& material);
  int texture_for(int gltf_texture, ColorSpace color_space);
  detail::TextureTransform material_uvs(int gltf_material) const;
  void frame_cameras();
  Texture decode_texture(int image_index, ColorSpace color_space) const;
  TextureSampler convert_sampler(int sampler_index) const;

  const tinygltf::Model& model_;
  const std::filesystem::path& file_;
  const GltfOptions& options_;
  GltfAsset asset_;
  std::map<int, std::uint32_t> materials_;  // glTF material (-1 = default) -> ours
  std::map<std::tuple<int, ColorSpace, int>, int> textures_;  // glTF image as colour or data, sampler -> ours
  std::uint64_t vertices_emitted_ = 0;
  bool quantized_ = std::find(model_.extensionsUsed.begin(), model_.extensionsUsed.end(), "KHR_mesh_quantization") !=
                    model_.extensionsUsed.end();
};

AccessorView Loader::view(int accessor_index, const std::string& what) const {
  if (accessor_index < 0 || std::size_t(accessor_index) >= model_.accessors.size())
    fail(what + ": accessor " + std::to_string(accessor_index) + " does not exist");
  const tinygltf::Accessor& accessor = model_.accessors[accessor_index];
  const std::string label = what + " (accessor " + std::to_string(accessor_index) + ")";
  if (accessor.sparse.isSparse) fail(label + ": sparse accessors are not supported");

  AccessorView result;
  result.count = accessor.count;
  result.component_type = accessor.componentType;
  result.components = component_count(accessor.type);
  result.normalized = accessor.normalized;
  const int component_size = component_bytes(accessor.componentType);
  if (component_size == 0) fail(label + ": unsupported component type " + std::to_string(accessor.componentType));
  if (result.components == 0) fail(label + ": unsupported accessor type " + std::to_string(accessor.type));
  const std::size_t element_bytes = std::size_t(component_size) * result.components;
  if (accessor.bufferView < 0) {  // all zeros: no buffer bounds its count, so cap it
    if (result.count > options_.max_vertices) fail(label + ": " + std::to_string(result.count) + " elements without data");
    return result;
  }
  if (std::size_t(accessor.bufferView) >= model_.bufferViews.size())
    fail(label + ": bufferView " + std::to_string(accessor.bufferView) + " does not exist");

  const tinygltf::BufferView& buffer_view = model_.bufferViews[accessor.bufferView];
  if (buffer_view.buffer < 0 || std::size_t(buffer_view.buffer) >= model_.buffers.size())
    fail(label + ": buffer " + std::to_string(buffer_view.buffer) + " does not exist");
  const tinygltf::Buffer& buffer = model_.buffers[buffer_view.buffer];
  if (buffer_view.byteOffset > buffer.data.size() || buffer_view.byteLength > buffer.data.size() - buffer_view.byteOffset)
    fail(label + ": bufferView " + std::to_string(accessor.bufferView) + " lies outside its buffer of " +
         std::to_string(buffer.data.size()) + " bytes");
  result.stride = buffer_view.byteStride != 0 ? buffer_view.byteStride : element_bytes;
  if (result.stride < element_bytes) fail(label + ": byteStride is smaller than one element");
  if (result.count > 0) {
    // Overflow-safe form of: byteOffset + (count - 1) * stride + element <= byteLength.
    const std::size_t length = buffer_view.byteLength;
    if (accessor.byteOffset > length || element_bytes > length - accessor.byteOffset ||
        result.count - 1 > (length - accessor.byteOffset - element_bytes) / result.stride)
      fail(label + ": " + std::to_string(result.count) + " elements do not fit in bufferView " +
           std::to_string(accessor.bufferView) + " (" + std::to_string(length) + " bytes)");
  }
  result.data = buffer.data.data() + buffer_view.byteOffset + accessor.byteOffset;
  return result;
}

float read_component(const unsigned char* p, int type, bool normalized) {
  switch (type) {
    case TINYGLTF_COMPONENT_TYPE_FLOAT: {
      float value;
      std::memcpy(&value, p, 4);
      return value;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: return normalized ? p[0] / 255.0f : p[0];
    case TINYGLTF_COMPONENT_TYPE_BYTE: {
      const auto value = static_cast<std::int8_t>(p[0]);
      return normalized ? std::max(value / 127.0f, -1.0f) : value;
    }
    case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
      std::uint16_t value;
      std::memcpy(&value, p, 2);
      return normalized ? value / 65535.0f : value;
    }
    case TINYGLTF_COMPONENT_TYPE_SHORT: {
      std::int16_t value;
      std::memcpy(&value, p, 2);
      return normalized ? std::max(value / 32767.0f, -1.0f) : value;
    }
    default: return 0.0f;
  }
}

template <int N>
std::vector<glm::vec<N, float>> Loader::read_vectors(int accessor_index, const std::string& what, Integers allowed) const {
  const AccessorView v = view(accessor_index, what);
  if (v.components != N) fail(what + ": expected " + std::to_string(N) + " components per element, accessor has " + std::to_string(v.components));
  const bool is_float = v.component_type == TINYGLTF_COMPONENT_TYPE_FLOAT;
  const bool is_unsigned = v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE ||
                           v.component_type == TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT;
  const bool is_signed = v.component_type == TINYGLTF_COMPONENT_TYPE_BYTE || v.component_type == TINYGLTF_COMPONENT_TYPE_SHORT;
  const bool ok = is_float || (allowed == Integers::normalized_unsigned && v.normalized && is_unsigned) ||
                  (allowed == Integers::any && (is_unsigned || is_signed));
  if (!ok)
    fail(what + ": component type " + std::to_string(v.component_type) + " is not supported here (expected float" +
         (allowed == Integers::normalized_unsigned ? " or normalized unsigned byte/short" : "") +
         (allowed == Integers::none ? "; quantized attributes need the file to use KHR_mesh_quantization)" : ")"));
  std::vector<glm::vec<N, float>> values(v.count, glm::vec<N, float>(0.0f));
  if (v.data == nullptr) return values;
  const int component_size = component_bytes(v.component_type);
  for (std::size_t i = 0; i < v.count; ++i)
    for (int c = 0; c < N; ++c)
      values[i][c] = read_component(v.data + i * v.stride + c * component_size, v.component_type, v.normalized);
  return values;
}

std::vector<std::uint32_t> Loader::read_indices(int accessor_index, const std::string& what) const {
  const AccessorView v = view(accessor_index, what);
  if (v.components != 1) fail(what + ": indices must be scalars");
  std::vector<std::uint32_t> indices(v.count, 0);
  if (v.data == nullptr) return indices;
  for (std::size_t i = 0; i < v.count; ++i) {
    const unsigned char* p = v.data + i * v.stride;
    switch (v.component_type) {
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_BYTE: indices[i] = p[0]; break;
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_SHORT: {
        std::uint16_t value;
        std::memcpy(&value, p, 2);
        indices[i] = value;
        break;
      }
      case TINYGLTF_COMPONENT_TYPE_UNSIGNED_INT: std::memcpy(&indices[i], p, 4); break;
      default: fail(what + ": index component type " + std::to_string(v.component_type) + " is not allowed");
    }
  }
  return indices;
}

// ---- hierarchy ----

void Loader::check_required_extensions() const {
  for (const std::string& extension : model_.extensionsRequired)
    if (!detail::is_supported_gltf_extension(extension)) fail("requires extension " + extension + ", which is not supported");
}

glm::mat4 local_matrix(const tinygltf::Node& node) {
  if (node.matrix.size() == 16) {
    glm::mat4 m;
    for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = static_cast<float>(node.matrix[i]);  // column-major
    return m;
  }
  glm::mat4 m(1.0f);
  if (node.translation.size() == 3)
    m[3] = glm::vec4(float(node.translation[0]), float(node.translation[1]), float(node.translation[2]), 1.0f);
  if (node.rotation.size() == 4) {
    const glm::quat q(float(node.rotation[3]), float(node.rotation[0]), float(node.rotation[1]), float(node.rotation[2]));
    m = m * glm::mat4_cast(glm::normalize(q));
  }
  if (node.scale.size() == 3)
    m = m * glm::mat4(glm::vec4(float(node.scale[0]), 0, 0, 0), glm::vec4(0, float(node.scale[1]), 0, 0),
                      glm::vec4(0, 0, float(node.scale[2]), 0), glm::vec4(0, 0, 0, 1));
  return m;
}

bool is_finite(const glm::mat4& m) {
  for (int c = 0; c < 4; ++c)
    for (int r = 0; r < 4; ++r)
      if (!std::isfinite(m[c][r])) return false;
  return true;
}

// glTF requires a forest: every node has at most one parent and a scene lists
// roots only. Checking that up front rules out cycles, so the walk terminates.
std::vector<int> Loader::root_nodes() const {
  const std::size_t node_count = model_.nodes.size();
  std::vector<int> parent(node_count, -1);
  for (std::size_t n = 0; n < node_count; ++n)
    for (int child : model_.nodes[n].children) {
      if (child < 0 || std::size_t(child) >= node_count)
        fail("node " + std::to_string(n) + " has child " + std::to_string(child) + ", which does not exist");
      if (parent[child] != -1 || child == int(n))
        fail("node " + std::to_string(child) + " has more than one parent (the node hierarchy must be a tree)");
      parent[child] = int(n);
    }

  std::vector<int> roots;
  const int scene = model_.defaultScene >= 0 ? model_.defaultScene : (model_.scenes.empty() ? -1 : 0);
  if (scene >= 0 && std::size_t(scene) >= model_.scenes.size()) fail("default scene " + std::to_string(scene) + " does not exist");
  if (scene < 0) {
    for (std::size_t n = 0; n < node_count; ++n)
      if (parent[n] == -1) roots.push_back(int(n));
    return roots;
  }
  std::set<int> seen;
  for (int node : model_.scenes[scene].nodes) {
    if (node < 0 || std::size_t(node) >= node_count) fail("scene lists node " + std::to_string(node) + ", which does not exist");
    if (parent[node] != -1) fail("scene lists node " + std::to_string(node) + ", which is not a root");
    if (!seen.insert(node).second) fail("scene lists node " + std::to_string(node) + " twice");
    roots.push_back(node);
  }
  return roots;
}

void Loader::visit_nodes() {
  std::vector<std::pair<int, glm::mat4>> stack;
  const std::vector<int> roots = root_nodes();
  for (auto root = roots.rbegin(); root != roots.rend(); ++root) stack.emplace_back(*root, options_.transform);  // pops in file order
  std::size_t visited = 0;
  while (!stack.empty()) {
    auto [node_index, parent_world] = stack.back();
    stack.pop_back();
    if (++visited > model_.nodes.size()) fail("node hierarchy has a cycle");
    const tinygltf::Node& node = model_.nodes[node_index];
    const glm::mat4 world = parent_world * local_matrix(node);
    if (!is_finite(world)) fail("node " + std::to_string(node_index) + " has a non-finite transform");
    if (node.mesh >= 0) add_mesh_instance(node.mesh, node.name, world);
    asset_.mesh_nodes.resize(asset_.meshes.size(), node_index);
    if (auto light = detail::node_light(model_, node, world, file_)) {
      asset_.lights.push_back(std::move(*light));
      asset_.light_nodes.push_back(node_index);
    }
    if (auto camera = detail::node_camera(model_, node, world, file_, asset_.warnings)) {
      asset_.cameras.push_back(std::move(*camera));
      asset_.camera_nodes.push_back(node_index);
    }
    for (auto child = node.children.rbegin(); child != node.children.rend(); ++child) stack.emplace_back(*child, world);
  }
}

// ---- primitives ----

std::vector<std::uint32_t> triangle_list(int mode, const std::vector<std::uint32_t>& in) {
  std::vector<std::uint32_t> out;
  if (mode == TINYGLTF_MODE_TRIANGLES) return in;
  for (std::size_t i = 0; i + 2 < in.size(); ++i) {
    if (mode == TINYGLTF_MODE_TRIANGLE_STRIP)  // keep every other triangle's winding consistent
      out.insert(out.end(), {in[i], in[i + 1 + i % 2], in[i + 2 - i % 2]});
    else  // fan
      out.insert(out.end(), {in[i + 1], in[i + 2], in[0]});
  }
  return out;
}

glm::vec3 safe_normalize(const glm::vec3& v) {
  const float length = glm::length(v);
  return (length > 0.0f && std::isfinite(length)) ? v / length : glm::vec3(0.0f, 1.0f, 0.0f);
}

glm::vec3 face_normal(const Mesh& mesh, std::size_t triangle) {
  const glm::vec3& a = mesh.positions[mesh.indices[3 * triangle]];
  const glm::vec3& b = mesh.positions[mesh.indices[3 * triangle + 1]];
  const glm::vec3& c = mesh.positions[mesh.indices[3 * triangle + 2]];
  return glm::cross(b - a, c - a);  // length = 2 x area: weights smooth normals by area
}

void generate_flat_normals(Mesh& mesh) {
  Mesh flat;
  for (std::size_t corner = 0; corner < mesh.indices.size(); ++corner) {
    flat.positions.push_back(mesh.positions[mesh.indices[corner]]);
    if (!mesh.uvs.empty()) flat.uvs.push_back(mesh.uvs[mesh.indices[corner]]);
    if (!mesh.tangents.empty()) flat.tangents.push_back(mesh.tangents[mesh.indices[corner]]);
  }
  flat.indices.resize(mesh.indices.size());
  std::iota(flat.indices.begin(), flat.indices.end(), 0u);
  for (std::size_t t = 0; t < flat.triangle_count(); ++t) {
    const glm::vec3 n = safe_normalize(face_normal(flat, t));
    flat.normals.insert(flat.normals.end(), {n, n, n});
  }
  mesh.positions = std::move(flat.positions);
  mesh.uvs = std::move(flat.uvs);
  mesh.tangents = std::move(flat.tangents);
  mesh.indices = std::move(flat.indices);
  mesh.normals = std::move(flat.normals);
}

void generate_smooth_normals(Mesh& mesh) {
  mesh.normals.assign(mesh.positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const glm::vec3 n = face_normal(mesh, t);
    for (int k = 0; k < 3; ++k) mesh.normals[mesh.indices[3 * t + k]] += n;
  }
  for (glm::vec3& n : mesh.normals) n = safe_normalize(n);
}

// A material's textures in glTF's order (Material::textures(); the first picks the UV set), with how each one's bytes
// are encoded.
struct TextureUse {
  const char* name;  // as glTF names the property
  int index;
  int texcoord;
  const tinygltf::ExtensionMap* extensions;
  ColorSpace color_space;
};

std::vector<TextureUse> texture_uses(const tinygltf::Material& m) {
  const auto& pbr = m.pbrMetallicRoughness;
  return {{"baseColorTexture", pbr.baseColorTexture.index, pbr.baseColorTexture.texCoord, &pbr.baseColorTexture.extensions, ColorSpace::srgb},
          {"metallicRoughnessTexture", pbr.metallicRoughnessTexture.index, pbr.metallicRoughnessTexture.texCoord,
           &pbr.metallicRoughnessTexture.extensions, ColorSpace::linear},
          {"normalTexture", m.normalTexture.index, m.normalTexture.texCoord, &m.normalTexture.extensions, ColorSpace::linear},
          {"occlusionTexture", m.occlusionTexture.index, m.occlusionTexture.texCoord, &m.occlusionTexture.extensions, ColorSpace::linear},
          {"emissiveTexture", m.emissiveTexture.index, m.emissiveTexture.texCoord, &m.emissiveTexture.extensions, ColorSpace::srgb}};
}


// Meshes are named after their node (instances of one glTF mesh differ), else the glTF mesh.
void Loader::add_mesh_instance(int mesh_index, const std::string& node_name, const glm::mat4& world) {
  if (std::size_t(mesh_index) >= model_.meshes.size()) fail("node uses mesh " + std::to_string(mesh_index) + ", which does not exist");
  const tinygltf::Mesh& mesh = model_.meshes[mesh_index];
  const std::string mesh_name = mesh.name.empty() ? "mesh " + std::to_string(mesh_index) : "mesh '" + mesh.name + "'";
  for (std::size_t p = 0; p < mesh.primitives.size(); ++p) {
    const tinygltf::Primitive& primitive = mesh.primitives[p];
    const std::string name = mesh_name + " primitive " + std::to_string(p);
    const int mode = primitive.mode < 0 ? TINYGLTF_MODE_TRIANGLES : primitive.mode;
    if (mode == TINYGLTF_MODE_POINTS) {
      ++asset_.point_primitives_skipped;
      continue;
    }
    if (mode > TINYGLTF_MODE_TRIANGLE_FAN) fail(name + ": unknown primitive mode " + std::to_string(mode));
    const auto position = primitive.attributes.find("POSITION");
    if (position == primitive.attributes.end()) fail(name + ": no POSITION attribute");
    const auto positions = read_vectors<3>(position->second, name + " POSITION", quantized_or(Integers::none));
    for (std::size_t i = 0; i < positions.size(); ++i)
      if (!std::isfinite(positions[i].x) || !std::isfinite(positions[i].y) || !std::isfinite(positions[i].z))
        fail(name + ": position " + std::to_string(i) + " is not finite");

    std::vector<std::uint32_t> indices;
    if (primitive.indices >= 0) {
      indices = read_indices(primitive.indices, name + " indices");
      for (std::uint32_t index : indices)
        if (index >= positions.size())
          fail(name + ": index " + std::to_string(index) + " is out of range (" + std::to_string(positions.size()) + " vertices)");
    } else {
      indices.resize(positions.size());
      std::iota(indices.begin(), indices.end(), 0u);
    }

    count_vertices(std::max(positions.size(), indices.size()), name);
    if (mode == TINYGLTF_MODE_LINE || mode == TINYGLTF_MODE_LINE_LOOP || mode == TINYGLTF_MODE_LINE_STRIP) {
      std::vector<glm::vec3> world_positions(positions.size());
      for (std::size_t i = 0; i < positions.size(); ++i) world_positions[i] = glm::vec3(world * glm::vec4(positions[i], 1.0f));
      add_lines(primitive, name, mode, indices, world_positions);
      continue;
    }
    if (mode == TINYGLTF_MODE_TRIANGLES && indices.size() % 3 != 0)
      fail(name + ": " + std::to_string(indices.size()) + " indices is not a whole number of triangles");
    Mesh out;
    out.name = (!node_name.empty() ? node_name : mesh.name.empty() ? "mesh" + std::to_string(mesh_index) : mesh.name) +
               (mesh.primitives.size() > 1 ? "#" + std::to_string(p) : "");
    out.positions = positions;
    asset_.meshes.push_back(std::move(out));
    add_triangles(primitive, name, triangle_list(mode, indices), world);
  }
}

void Loader::count_vertices(std::size_t count, const std::string& name) {
  vertices_emitted_ += count;
  if (vertices_emitted_ > options_.max_vertices)
    fail(name + ": the file expands to more than " + std::to_string(options_.max_vertices) +
         " vertices in total (max_vertices)");
}

bool is_finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

// Some exporters write (0, 0, 0) normals; shading with them gives NaNs.
void Loader::repair_zero_normals(Mesh& mesh, const std::string& name) {
  std::size_t zero = 0;
  for (const glm::vec3& n : mesh.normals) zero += glm::dot(n, n) < 1e-20f;
  if (zero == 0) return;
  Mesh smooth = mesh;
  generate_smooth_normals(smooth);
  for (std::size_t i = 0; i < mesh.normals.size(); ++i)
    if (glm::dot(mesh.normals[i], mesh.normals[i]) < 1e-20f) mesh.normals[i] = smooth.normals[i];
  asset_.warnings.push_back(name + ": " + std::to_string(zero) + " zero-length normals replaced by smooth normals");
}

// Per-vertex tangents from UV derivatives (Lengyel, "Computing Tangent Space Basis
// Vectors for an Arbitrary Mesh", 2001), not MikkTSpace: each triangle's dP/dU and
// dP/dV summed at its corners, the sum made orthogonal to the vertex normal and unit
// length. The handedness compares cross(normal, tangent) with -dP/dV, the image's up
// (glTF's V runs down the image; normal textures' +Y points up it). Returns how many
// vertices had no usable UV derivatives; they get some tangent in the surface.
std::size_t generate_tangents(Mesh& mesh) {
  std::vector<glm::vec3> along_u(mesh.positions.size(), glm::vec3(0.0f));
  std::vector<glm::vec3> along_v(mesh.positions.size(), glm::vec3(0.0f));
  for (std::size_t t = 0; t < mesh.triangle_count(); ++t) {
    const std::uint32_t* corner = &mesh.indices[3 * t];
    const glm::vec3 e1 = mesh.positions[corner[1]] - mesh.positions[corner[0]];
    const glm::vec3 e2 = mesh.positions[corner[2]] - mesh.positions[corner[0]];
    const glm::vec2 d1 = mesh.uvs[corner[1]] - mesh.uvs[corner[0]];
    const glm::vec2 d2 = mesh.uvs[corner[2]] - mesh.uvs[corner[0]];
    const float uv_area = d1.x * d2.y - d2.x * d1.y;
    if (!(std::abs(uv_area) > 1e-20f)) continue;  // no UV extent (or NaN): says nothing about direction
    const glm::vec3 dp_du = (e1 * d2.y - e2 * d1.y) / uv_area;
    const glm::vec3 dp_dv = (e2 * d1.x - e1 * d2.x) / uv_area;
    if (!is_finite(dp_du) || !is_finite(dp_dv)) continue;
    for (int k = 0; k < 3; ++k) {
      along_u[corner[k]] += dp_du;
      along_v[corner[k]] += dp_dv;
    }
  }
  std::size_t degenerate = 0;
  mesh.tangents.resize(mesh.positions.size());
  for (std::size_t i = 0; i < mesh.positions.size(); ++i) {
    const glm::vec3& n = mesh.normals[i];
    glm::vec3 t = along_u[i] - n * glm::dot(n, along_u[i]);
    if (!(glm::dot(t, t) > 1e-24f)) {
      ++degenerate;  // any direction in the surface: the normal texture's X and Y get some frame
      t = std::abs(n.x) < 0.9f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
      t -= n * glm::dot(n, t);
    }
    t = glm::normalize(t);
    const float handedness = glm::dot(glm::cross(n, t), -along_v[i]) < 0.0f ? -1.0f : 1.0f;
    mesh.tangents[i] = glm::vec4(t, handedness);
  }
  return degenerate;
}

// Tangents for a mesh whose material has a normal texture: the file's, made unit and
// orthogonal to the (final) normals, else generated from the UVs.
void Loader::finish_tangents(Mesh& mesh, const std::string& name) {
  if (mesh.uvs.empty()) {
    mesh.tangents.clear();
    asset_.warnings.push_back(name + ": its material has a normal texture but the primitive has no texture coordinates; "
                              "the normal texture is not applied");
    return;
  }
  if (mesh.tangents.empty()) {
    const std::size_t degenerate = generate_tangents(mesh);
    if (degenerate > 0)
      asset_.warnings.push_back(name + ": " + std::to_string(degenerate) +
                                " vertices have no usable UV derivatives for a tangent; the normal texture is oriented arbitrarily there");
    return;
  }
  for (std::size_t i = 0; i < mesh.tangents.size(); ++i) {
    const glm::vec3& n = mesh.normals[i];
    glm::vec3 t = glm::vec3(mesh.tangents[i]);
    t -= n * glm::dot(n, t);
    mesh.tangents[i] = glm::vec4(glm::dot(t, t) > 1e-24f ? glm::normalize(t) : glm::vec3(0.0f), mesh.tangents[i].w);
  }
}

// Finishes asset_.meshes.back(), whose positions are still in mesh space.
void Loader::add_triangles(const tinygltf::Primitive& primitive, const std::string& name,
                           std::vector<std::uint32_t> indices, const glm::mat4& world) {
  Mesh& mesh = asset_.meshes.back();
  mesh.material = material_index(primitive.material);
  const std::size_t vertex_count = mesh.positions.size();
  const detail::TextureTransform uv_set = material_uvs(primitive.material);
  const auto uv = primitive.attributes.find("TEXCOORD_" + std::to_string(uv_set.texcoord));
  if (uv != primitive.attributes.end()) {
    mesh.uvs = read_vectors<2>(uv->second, name + " " + uv->first, quantized_or(Integers::normalized_unsigned));
    if (mesh.uvs.size() != vertex_count) fail(name + ": " + uv->first + " count differs from POSITION count");
    if (uv_set.present)  // KHR_texture_transform, applied once here for every texture of the material
      for (glm::vec2& coordinate : mesh.uvs) coordinate = glm::vec2(uv_set.matrix * glm::vec3(coordinate, 1.0f));
  }
  const auto normal = primitive.attributes.find("NORMAL");
  if (normal != primitive.attributes.end()) {
    mesh.normals = read_vectors<3>(normal->second, name + " NORMAL", quantized_or(Integers::none));
    if (mesh.normals.size() != vertex_count) fail(name + ": NORMAL count differs from POSITION count");
    for (std::size_t i = 0; i < vertex_count; ++i)
      if (!is_finite(mesh.normals[i])) fail(name + ": normal " + std::to_string(i) + " is not finite");
  }

  const bool needs_tangents = asset_.materials[mesh.material].normal_texture >= 0;
  const auto tangent = primitive.attributes.find("TANGENT");
  if (needs_tangents && tangent != primitive.attributes.end()) {
    mesh.tangents = read_vectors<4>(tangent->second, name + " TANGENT", quantized_or(Integers::none));
    if (mesh.tangents.size() != vertex_count) fail(name + ": TANGENT count differs from POSITION count");
    for (std::size_t i = 0; i < vertex_count; ++i)
      if (!std::isfinite(mesh.tangents[i].x) || !std::isfinite(mesh.tangents[i].y) || !std::isfinite(mesh.tangents[i].z))
        fail(name + ": tangent " + std::to_string(i) + " is not finite");
  }

  const glm::mat3 linear(world);
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(linear));
  const bool mirrored = glm::determinant(linear) < 0.0f;
  for (glm::vec3& p : mesh.positions) p = glm::vec3(world * glm::vec4(p, 1.0f));
  for (glm::vec3& n : mesh.normals) {
    const glm::vec3 transformed = normal_matrix * n;
    n = glm::dot(transformed, transformed) > 0.0f ? glm::normalize(transformed) : glm::vec3(0.0f);
  }
  for (glm::vec4& t : mesh.tangents)  // tangents lie in the surface: they transform as positions do
    t = glm::vec4(linear * glm::vec3(t), (t.w < 0.0f) != mirrored ? -1.0f : 1.0f);  // a mirror flips the bitangent
  if (mirrored)  // a mirror turns CCW into CW: swap to keep front faces CCW
    for (std::size_t t = 0; t + 2 < indices.size(); t += 3) std::swap(indices[t + 1], indices[t + 2]);
  mesh.indices = std::move(indices);

  if (mesh.normals.empty()) {
    if (options_.missing_normals == NormalGeneration::flat)
      generate_flat_normals(mesh);
    else
      generate_smooth_normals(mesh);
  } else {
    repair_zero_normals(mesh, name);
  }
  if (needs_tangents) finish_tangents(mesh, name);
  for (const glm::vec3& p : mesh.positions) {
    if (!is_finite(p)) fail(name + ": a position is not finite after the node transforms");
    mesh.bounds.extend(p);
  }
  if (mesh.indices.empty()) asset_.meshes.pop_back();  // e.g. a strip of two vertices
}

void Loader::add_lines(const tinygltf::Primitive& primitive, const std::string& name, int mode, const std::vector<std::uint32_t>& indices,
                       const std::vector<glm::vec3>& positions) {
  glm::vec3 color(1.0f);
  if (primitive.material >= 0) {
    const std::uint32_t m = material_index(primitive.material);
    color = glm::vec3(asset_.materials[m].base_color_factor);
  }
  HairGroom& hair = asset_.line_strands;
  if (hair.strand_offsets.empty()) hair.strand_offsets.push_back(0);
  auto start_strand = [&] {
    hair.strand_offsets.push_back(static_cast<std::uint32_t>(hair.points.size()));
    hair.strand_width.push_back(1.0f);
    hair.strand_opacity.push_back(1.0f);
    hair.strand_color.push_back(color);
  };
  auto append = [&](std::uint32_t index) {
    hair.points.push_back(positions[index]);
    hair.strand_offsets.back() = static_cast<std::uint32_t>(hair.points.size());
  };

  if (mode == TINYGLTF_MODE_LINE) {
    if (indices.size() % 2 != 0) fail(name + ": LINES with an odd number of indices (" + std::to_string(indices.size()) + ")");
    for (std::size_t i = 0; i < indices.size(); i += 2) {
      const bool continues = i > 0 && indices[i] == indices[i - 1];
      if (!continues) {
        start_strand();
        append(indices[i]);
      }
      append(indices[i + 1]);
    }
    return;
  }
  if (indices.size() < 2) return;
  start_strand();
  for (std::uint32_t index : indices) append(index);
  if (mode == TINYGLTF_MODE_LINE_LOOP) append(indices.front());
}

// ---- materials and textures ----

std::uint32_t Loader::material_index(int gltf_material) {
  if (gltf_material >= 0 && std::size_t(gltf_material) >= model_.materials.size())
    fail("primitive uses material " + std::to_string(gltf_material) + ", which does not exist");
  const auto found = materials_.find(gltf_material);
  if (found != materials_.end()) return found->second;
  Material material = gltf_material < 0 ? Material{"default"} : convert_material(model_.materials[gltf_material]);
  asset_.materials.push_back(std::move(material));
  const auto index = static_cast<std::uint32_t>(asset_.materials.size() - 1);
  materials_[gltf_material] = index;
  return index;
}

Material Loader::convert_material(const tinygltf::Material& source) {
  Material material;
  material.name = source.name;
  const std::string label = "material '" + source.name + "'";
  const auto& factor = source.pbrMetallicRoughness.baseColorFactor;
  if (factor.size() != 4) fail(label + ": baseColorFactor needs 4 numbers");
  material.base_color_factor = glm::vec4(float(factor[0]), float(factor[1]), float(factor[2]), float(factor[3]));
  if (source.emissiveFactor.size() == 3)
    material.emissive = glm::vec3(float(source.emissiveFactor[0]), float(source.emissiveFactor[1]), float(source.emissiveFactor[2]));
  const auto strength = source.extensions.find("KHR_materials_emissive_strength");
  if (strength != source.extensions.end() && strength->second.Has("emissiveStrength") &&
      strength->second.Get("emissiveStrength").IsNumber())
    material.emissive *= float(strength->second.Get("emissiveStrength").GetNumberAsDouble());

  if (source.alphaMode == "OPAQUE") material.alpha_mode = AlphaMode::opaque;
  else if (source.alphaMode == "MASK") material.alpha_mode = AlphaMode::mask;
  else if (source.alphaMode == "BLEND") material.alpha_mode = AlphaMode::blend;
  else fail(label + ": unknown alphaMode '" + source.alphaMode + "'");
  material.alpha_cutoff = float(source.alphaCutoff);
  material.double_sided = source.doubleSided;
  material.metallic_factor = float(source.pbrMetallicRoughness.metallicFactor);
  material.roughness_factor = float(source.pbrMetallicRoughness.roughnessFactor);
  material.normal_scale = float(source.normalTexture.scale);
  material.occlusion_strength = float(source.occlusionTexture.strength);
  const float values[] = {material.base_color_factor.r, material.base_color_factor.g, material.base_color_factor.b,
                          material.base_color_factor.a, material.emissive.r, material.emissive.g, material.emissive.b,
                          material.alpha_cutoff, material.metallic_factor, material.roughness_factor,
                          material.normal_scale, material.occlusion_strength};
  for (float value : values)
    if (!std::isfinite(value)) fail(label + ": has a non-finite factor");
  for (auto [factor, what] : {std::pair{&material.metallic_factor, "metallicFactor"}, {&material.roughness_factor, "roughnessFactor"},
                              {&material.occlusion_strength, "occlusionTexture.strength"}})
    if (*factor < 0.0f || *factor > 1.0f) {
      asset_.warnings.push_back(label + ": " + what + " " + std::to_string(*factor) + " is outside 0..1; clamped");
      *factor = std::clamp(*factor, 0.0f, 1.0f);
    }
  convert_textures(source, label, material);
  return material;
}

// The one UV set, and KHR_texture_transform, that a material's textures are read
// through: those of its first texture (texture_uses order). The loader bakes the
// transform into the mesh's UVs, as the textures of one material nearly always share it.
detail::TextureTransform Loader::material_uvs(int gltf_material) const {
  if (gltf_material < 0 || std::size_t(gltf_material) >= model_.materials.size()) return {};
  const tinygltf::Material& material = model_.materials[gltf_material];
  for (const TextureUse& use : texture_uses(material))
    if (use.index >= 0)
      return detail::texture_transform(*use.extensions, std::max(0, use.texcoord), "material '" + material.name + "' " + use.name, file_);
  return {};
}

// The material's textures, each decoded in its colour space. A texture on another UV
// set than the material's (material_uvs) is dropped, one with another transform is
// read through the material's, each with a warning.
void Loader::convert_textures(const tinygltf::Material& source, const std::string& label, Material& material) {
  const std::array<int*, 5> targets = material.textures();  // in texture_uses' order
  const std::vector<TextureUse> uses = texture_uses(source);
  std::optional<detail::TextureTransform> first;
  for (std::size_t i = 0; i < uses.size(); ++i) {
    const TextureUse& use = uses[i];
    if (use.index < 0) continue;
    const detail::TextureTransform uvs = detail::texture_transform(*use.extensions, std::max(0, use.texcoord), label + " " + use.name, file_);
    if (!first) first = uvs;
    if (uvs.texcoord != first->texcoord) {
      asset_.warnings.push_back(label + ": " + use.name + " reads TEXCOORD_" + std::to_string(uvs.texcoord) +
                                " but the material's other textures read TEXCOORD_" + std::to_string(first->texcoord) +
                                " (one UV set per material is supported); the " + use.name + " is not applied");
      continue;
    }
    if (uvs.matrix != first->matrix)
      asset_.warnings.push_back(label + ": " + use.name + "'s KHR_texture_transform differs from the material's first "
                                "texture's (one transform per material is supported); it is sampled through that one");
    *targets[i] = texture_for(use.index, use.color_space);
  }
}

int Loader::texture_for(int gltf_texture, ColorSpace color_space) {
  if (gltf_texture < 0) return -1;
  if (std::size_t(gltf_texture) >= model_.textures.size())
    fail("material uses texture " + std::to_string(gltf_texture) + ", which does not exist");
  const int image = model_.textures[gltf_texture].source;
  if (image < 0 || std::size_t(image) >= model_.images.size())
    fail("texture " + std::to_string(gltf_texture) + " has no image we can decode (source " + std::to_string(image) +
         "; extension-only sources such as KTX2 or WebP are not supported)");
  const int sampler = model_.textures[gltf_texture].sampler;
  const auto found = textures_.find({image, color_space, sampler});
  if (found != textures_.end()) return found->second;
  Texture texture = decode_texture(image, color_space);
  texture.sampler = convert_sampler(sampler);
  if (texture.sampler.mipmapped) generate_mips(texture);
  asset_.textures.push_back(std::move(texture));
  return textures_[{image, color_space, sampler}] = int(asset_.textures.size() - 1);
}

// glTF's sampler enums (OpenGL's values); absent members keep TextureSampler's defaults.
TextureSampler Loader::convert_sampler(int sampler_index) const {
  TextureSampler sampler;
  if (sampler_index < 0) return sampler;
  if (std::size_t(sampler_index) >= model_.samplers.size()) fail("texture uses sampler " + std::to_string(sampler_index) + ", which does not exist");
  const tinygltf::Sampler& source = model_.samplers[sampler_index];
  const std::string label = "sampler " + std::to_string(sampler_index);
  auto wrap = [&](int mode, const char* what) {
    switch (mode) {
      case TINYGLTF_TEXTURE_WRAP_REPEAT: return TextureWrap::repeat;
      case TINYGLTF_TEXTURE_WRAP_CLAMP_TO_EDGE: return TextureWrap::clamp_to_edge;
      case TINYGLTF_TEXTURE_WRAP_MIRRORED_REPEAT: return TextureWrap::mirrored_repeat;
      default: fail(label + ": unknown " + what + " " + std::to_string(mode));
    }
  };
  sampler.wrap_u = wrap(source.wrapS, "wrapS");
  sampler.wrap_v = wrap(source.wrapT, "wrapT");
  switch (source.magFilter) {
    case -1: break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST: sampler.mag = TextureFilter::nearest; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: sampler.mag = TextureFilter::linear; break;
    default: fail(label + ": unknown magFilter " + std::to_string(source.magFilter));
  }
  using F = TextureFilter;
  switch (source.minFilter) {
    case -1: break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST: sampler.min = F::nearest, sampler.mipmapped = false; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR: sampler.min = F::linear, sampler.mipmapped = false; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_NEAREST: sampler.min = F::nearest, sampler.mip = F::nearest; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_NEAREST: sampler.min = F::linear, sampler.mip = F::nearest; break;
    case TINYGLTF_TEXTURE_FILTER_NEAREST_MIPMAP_LINEAR: sampler.min = F::nearest, sampler.mip = F::linear; break;
    case TINYGLTF_TEXTURE_FILTER_LINEAR_MIPMAP_LINEAR: sampler.min = F::linear, sampler.mip = F::linear; break;
    default: fail(label + ": unknown minFilter " + std::to_string(source.minFilter));
  }
  return sampler;
}

Texture Loader::decode_texture(int image_index, ColorSpace color_space) const {
  const tinygltf::Image& image = model_.images[image_index];
  const bool named_file = !image.uri.empty() && image.uri.rfind("data:", 0) != 0;
  const std::string label = "image " + std::to_string(image_index) + (named_file ? " '" + image.uri + "'" : "");
  if (image.image.empty()) fail(label + " has no data (missing file or empty bufferView)");
  Texture texture;
  texture.name = !image.name.empty() ? image.name : named_file ? image.uri : "image" + std::to_string(image_index);
  texture.color_space = color_space;
  std::string error;
  if (!detail::decode_rgba8(image.image, options_.max_texture_size, texture, error))
    fail(label + " cannot be decoded: " + error);
  return texture;
}

// A glTF camera has no target: put it where the view's axis passes the asset's centre
// (the viewer orbits it), and bound an infinite far plane by the asset's farthest corner.
void Loader::frame_cameras() {
  for (Camera& camera : asset_.cameras) {
    const glm::vec3 forward = camera.target - camera.position;  // unit (node_camera)
    float focus = 1.0f, farthest = 0.0f;
    if (!asset_.bounds.empty()) {
      focus = glm::dot(asset_.bounds.center() - camera.position, forward);
      for (int corner = 0; corner < 8; ++corner)
        farthest = std::max(farthest, glm::length(asset_.bounds.corner(corner) - camera.position));
    }
    camera.target = camera.position + forward * std::max(focus, 10.0f * camera.near_plane);
    if (camera.far_plane == 0.0f) camera.far_plane = std::max(2.0f * farthest, 1000.0f * camera.near_plane);
  }
}

// The node hierarchy at rest, and every animation's translation, rotation and scale
// channels on it (all animations play together; "weights" is left to the morph-target
// warning).
void Loader::read_node_animation() {
  auto nodes = std::make_shared<NodeAnimation>();
  nodes->nodes.resize(model_.nodes.size());
  for (std::size_t n = 0; n < model_.nodes.size(); ++n) {
    const tinygltf::Node& source = model_.nodes[n];
    NodeAnimation::Node& node = nodes->nodes[n];
    for (int child : source.children) nodes->nodes[std::size_t(child)].parent = int(n);  // checked by root_nodes()
    node.has_matrix = source.matrix.size() == 16;
    node.matrix = local_matrix(source);
    if (source.translation.size() == 3) node.translation = glm::vec3(float(source.translation[0]), float(source.translation[1]), float(source.translation[2]));
    if (source.rotation.size() == 4)
      node.rotation = glm::normalize(glm::quat(float(source.rotation[3]), float(source.rotation[0]), float(source.rotation[1]), float(source.rotation[2])));
    if (source.scale.size() == 3) node.scale = glm::vec3(float(source.scale[0]), float(source.scale[1]), float(source.scale[2]));
  }
  for (std::size_t a = 0; a < model_.animations.size(); ++a) {
    const tinygltf::Animation& animation = model_.animations[a];
    for (std::size_t c = 0; c < animation.channels.size(); ++c) {
      const tinygltf::AnimationChannel& channel = animation.channels[c];
      const std::string what = "animation " + std::to_string(a) + " channel " + std::to_string(c);
      if (channel.target_path == "weights" || channel.target_node < 0) continue;
      if (std::size_t(channel.target_node) >= model_.nodes.size())
        fail(what + ": targets node " + std::to_string(channel.target_node) + ", which does not exist");
      NodeAnimation::Node& node = nodes->nodes[std::size_t(channel.target_node)];
      if (node.has_matrix) fail(what + ": targets node " + std::to_string(channel.target_node) + ", which has a matrix (glTF forbids animating it)");
      if (channel.target_path == "translation") node.translation_track = read_channel<3>(animation, channel, what);
      else if (channel.target_path == "scale") node.scale_track = read_channel<3>(animation, channel, what);
      else if (channel.target_path == "rotation") node.rotation_track = read_channel<4>(animation, channel, what);
      else fail(what + ": unknown target path '" + channel.target_path + "'");
    }
  }
  asset_.nodes = std::move(nodes);
}

// One channel's sampler as a track: its input (seconds, increasing) and output (values,
// and for CUBICSPLINE an in-tangent, value and out-tangent per key).
template <int N>
Track<N> Loader::read_channel(const tinygltf::Animation& animation, const tinygltf::AnimationChannel& channel,
                              const std::string& what) const {
  if (channel.sampler < 0 || std::size_t(channel.sampler) >= animation.samplers.size())
    fail(what + ": sampler " + std::to_string(channel.sampler) + " does not exist");
  const tinygltf::AnimationSampler& sampler = animation.samplers[std::size_t(channel.sampler)];
  Track<N> track;
  if (sampler.interpolation == "STEP") track.interpolation = Interpolation::step;
  else if (sampler.interpolation == "LINEAR") track.interpolation = Interpolation::linear;
  else if (sampler.interpolation == "CUBICSPLINE") track.interpolation = Interpolation::cubic;
  else fail(what + ": unknown interpolation '" + sampler.interpolation + "'");
  for (const glm::vec<1, float>& time : read_vectors<1>(sampler.input, what + " input", Integers::none)) {
    if (!std::isfinite(time.x) || (!track.times.empty() && !(time.x > track.times.back())))
      fail(what + " input: key times must be finite and increasing");
    track.times.push_back(time.x);
  }
  const auto output = read_vectors<N>(sampler.output, what + " output", Integers::any);
  const std::size_t per_key = track.interpolation == Interpolation::cubic ? 3 : 1;
  if (track.times.empty() || output.size() != track.times.size() * per_key)
    fail(what + ": " + std::to_string(output.size()) + " output values for " + std::to_string(track.times.size()) + " keys");
  for (std::size_t k = 0; k < track.times.size(); ++k) {
    if (per_key == 3) {
      track.in_tangents.push_back(output[3 * k]);
      track.values.push_back(output[3 * k + 1]);
      track.out_tangents.push_back(output[3 * k + 2]);
    } else {
      track.values.push_back(output[k]);
    }
  }
  for (const auto& value : track.values)
    for (int i = 0; i < N; ++i)
      if (!std::isfinite(value[i])) fail(what + " output: a value is not finite");
  return track;
}

GltfAsset Loader::load() {
  check_required_extensions();
  visit_nodes();
  read_node_animation();
  if (!asset_.line_strands.points.empty()) {
    asset_.line_strands.name = file_.stem().string();
    asset_.line_strands.width_kind = StrandWidth::relative;
    validate_groom(asset_.line_strands, file_);
  } else {
    asset_.line_strands = HairGroom{};
  }
  for (const Mesh& mesh : asset_.meshes) asset_.bounds.extend(mesh.bounds);
  asset_.bounds.extend(asset_.line_strands.bounds);
  frame_cameras();
  for (std::string& warning : detail::ignored_content_warnings(model_, file_)) asset_.warnings.push_back(std::move(warning));
  return std::move(asset_);
}

}  // namespace

GltfAsset parse_gltf(std::span<const std::byte> bytes, const std::filesystem::path& name, const GltfOptions& options) {
  std::string warnings;
  const tinygltf::Model model = parse_model(bytes, name, options, warnings);
  GltfAsset asset = Loader(model, name, options).load();
  std::size_t start = 0;
  while (start < warnings.size()) {  // tinygltf separates warnings with newlines
    const std::size_t end = std::min(warnings.find('\n', start), warnings.size());
    if (end > start) asset.warnings.push_back(warnings.substr(start, end - start));
    start = end + 1;
  }
  return asset;
}

GltfAsset load_gltf(const std::filesystem::path& file, const GltfOptions& options) {
  return parse_gltf(detail::read_file_bytes(file, options.max_file_bytes), file, options);
}

}  // namespace avsm::scene
