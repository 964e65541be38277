#include "scene/gltf_extensions.h"

#include "scene/load_error.h"

#include <glm/gtc/constants.hpp>

#include <algorithm>
#include <cmath>
#include <map>
#include <set>

namespace avsm::scene::detail {
namespace {

// What of a file each known-but-unread extension leaves out, for its warning.
const std::map<std::string, std::string>& ignored_extension_effects() {
  static const std::map<std::string, std::string> effects = {
      {"KHR_materials_clearcoat", "the clear-coat layer is not shaded (the base layer is)"},
      {"KHR_materials_transmission", "transmission is not shaded (surfaces are opaque)"},
      {"KHR_materials_volume", "the volume inside surfaces is not shaded"},
      {"KHR_materials_ior", "the index of refraction is taken as 1.5"},
      {"KHR_materials_specular", "the specular layer's strength and colour are the default"},
      {"KHR_materials_sheen", "the sheen layer is not shaded"},
      {"KHR_materials_iridescence", "iridescence is not shaded"},
      {"KHR_materials_anisotropy", "specular highlights are isotropic"},
      {"KHR_materials_unlit", "unlit materials are shaded as lit"},
      {"KHR_materials_variants", "the default material of each primitive is used"},
      {"KHR_materials_pbrSpecularGlossiness", "the metallic-roughness fallback is used"},
      {"KHR_texture_basisu", "textures are read from their PNG or JPEG fallback only"},
      {"EXT_texture_webp", "textures are read from their PNG or JPEG fallback only"},
      {"KHR_draco_mesh_compression", "the uncompressed fallback of each primitive is read"},
      {"EXT_meshopt_compression", "the uncompressed fallback buffers are read"},
      {"EXT_mesh_gpu_instancing", "each instanced node is drawn once, at its own transform"},
      {"KHR_animation_pointer", "animations of material and light properties are not played"},
  };
  return effects;
}

double number_or(const tinygltf::Value& object, const char* key, double fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  return value.IsNumber() ? value.GetNumberAsDouble() : fallback;
}

glm::vec2 vec2_or(const tinygltf::Value& object, const char* key, glm::vec2 fallback) {
  if (!object.IsObject() || !object.Has(key)) return fallback;
  const tinygltf::Value& value = object.Get(key);
  if (!value.IsArray() || value.ArrayLen() != 2 || !value.Get(0).IsNumber() || !value.Get(1).IsNumber()) return fallback;
  return {float(value.Get(0).GetNumberAsDouble()), float(value.Get(1).GetNumberAsDouble())};
}

std::string node_label(const tinygltf::Node& node) { return node.name.empty() ? "a node" : "node '" + node.name + "'"; }

glm::vec3 world_forward(const glm::mat4& world) {  // the node's -Z, as lights and cameras look
  const glm::vec3 forward = -glm::vec3(world[2]);
  const float length = glm::length(forward);
  return length > 0.0f && std::isfinite(length) ? forward / length : glm::vec3(0.0f, 0.0f, -1.0f);
}

}  // namespace

bool is_supported_gltf_extension(const std::string& extension) {
  static const std::set<std::string> supported = {"KHR_materials_emissive_strength", "KHR_texture_transform",
                                                  "KHR_mesh_quantization", "KHR_lights_punctual"};
  return supported.count(extension) > 0;
}

std::vector<std::string> ignored_content_warnings(const tinygltf::Model& model, const std::filesystem::path& file) {
  std::vector<std::string> warnings;
  const std::string name = file.filename().string();
  for (const std::string& extension : model.extensionsUsed) {
    if (is_supported_gltf_extension(extension)) continue;
    const auto effect = ignored_extension_effects().find(extension);
    warnings.push_back("uses extension " + extension + ", which is not supported: " +
                       (effect != ignored_extension_effects().end() ? effect->second : "it is ignored"));
  }
  for (std::size_t s = 0; s < model.skins.size(); ++s)
    warnings.push_back("skin " + std::to_string(s) + (model.skins[s].name.empty() ? "" : " ('" + model.skins[s].name + "')") +
                       " of " + name + " is shown in its bind pose (skinning is not supported)");
  for (const tinygltf::Mesh& mesh : model.meshes) {
    std::size_t targets = 0;
    for (const tinygltf::Primitive& primitive : mesh.primitives) targets = std::max(targets, primitive.targets.size());
    if (targets > 0)
      warnings.push_back("mesh '" + mesh.name + "' of " + name + " has " + std::to_string(targets) +
                         " morph targets; it is shown without them (morph targets are not supported)");
  }
  if (model.animations.size() > 1)
    warnings.push_back(std::to_string(model.animations.size()) + " animations of " + name +
                       " play together, as one timeline (choosing one is not supported)");
  return warnings;
}

std::optional<Light> node_light(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                                const std::filesystem::path& file) {
  const auto extension = node.extensions.find("KHR_lights_punctual");
  if (extension == node.extensions.end()) return std::nullopt;
  const std::string where = node_label(node) + ": KHR_lights_punctual";
  const tinygltf::Value& light_ref = extension->second;
  if (!light_ref.IsObject() || !light_ref.Has("light") || !light_ref.Get("light").IsNumber())
    throw LoadError(file, where + " has no 'light' index");
  const double index = light_ref.Get("light").GetNumberAsDouble();
  if (!(index >= 0.0 && index < double(model.lights.size())) || index != std::floor(index))
    throw LoadError(file, where + " uses light " + std::to_string(index) + ", which does not exist (" +
                              std::to_string(model.lights.size()) + " lights)");
  const tinygltf::Light& source = model.lights[std::size_t(index)];
  const std::string label = "KHR_lights_punctual light " + std::to_string(std::size_t(index));

  Light light;
  light.name = !node.name.empty() ? node.name : !source.name.empty() ? source.name : "light " + std::to_string(std::size_t(index));
  if (source.type == "directional") light.type = LightType::directional;
  else if (source.type == "point") light.type = LightType::point;
  else if (source.type == "spot") light.type = LightType::spot;
  else throw LoadError(file, label + ": unknown type '" + source.type + "' (directional, point or spot)");
  if (source.color.size() == 3) light.color = glm::vec3(float(source.color[0]), float(source.color[1]), float(source.color[2]));
  else if (!source.color.empty()) throw LoadError(file, label + ": color needs 3 numbers");
  // Photometric to ours: our value is the radiance a white Lambertian surface reflects
  // (content/README.md), which is E / pi for an illuminance E (lux, or cd at 1 m).
  light.intensity = float(source.intensity / glm::pi<double>());
  light.range = float(source.range);
  if (!glm::all(glm::greaterThanEqual(light.color, glm::vec3(0.0f))) || !std::isfinite(light.intensity) ||
      light.intensity < 0.0f || !std::isfinite(light.range) || light.range < 0.0f)
    throw LoadError(file, label + ": color, intensity and range must be finite and >= 0");
  light.position = glm::vec3(world[3]);
  light.direction = world_forward(world);
  if (light.type == LightType::spot) {
    // Our cone must open less than 90 degrees (a spot light's map is one perspective view).
    const float widest = glm::radians(89.0f);
    light.outer_cone_angle = std::min(float(source.spot.outerConeAngle), widest);
    light.inner_cone_angle = std::clamp(float(source.spot.innerConeAngle), 0.0f, light.outer_cone_angle);
    if (!(source.spot.outerConeAngle > 0.0) || !(source.spot.innerConeAngle >= 0.0))
      throw LoadError(file, label + ": spot cone angles must be > 0 (outer) and >= 0 (inner)");
  }
  return light;
}

std::optional<Camera> node_camera(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                                  const std::filesystem::path& file, std::vector<std::string>& warnings) {
  if (node.camera < 0) return std::nullopt;
  if (std::size_t(node.camera) >= model.cameras.size())
    throw LoadError(file, node_label(node) + " uses camera " + std::to_string(node.camera) + ", which does not exist");
  const tinygltf::Camera& source = model.cameras[node.camera];
  const std::string label = "camera " + std::to_string(node.camera);
  if (source.type != "perspective") {
    warnings.push_back(label + " is " + source.type + "; only perspective cameras are supported, it is left out");
    return std::nullopt;
  }
  const tinygltf::PerspectiveCamera& lens = source.perspective;
  if (!(lens.yfov > 0.0 && lens.yfov < glm::pi<double>()) || !(lens.znear > 0.0) || !(lens.zfar == 0.0 || lens.zfar > lens.znear))
    throw LoadError(file, label + ": needs 0 < yfov < pi, znear > 0 and zfar > znear (or no zfar)");
  Camera camera;
  camera.name = !node.name.empty() ? node.name : !source.name.empty() ? source.name : "camera " + std::to_string(node.camera);
  camera.position = glm::vec3(world[3]);
  camera.target = camera.position + world_forward(world);
  const glm::vec3 up = glm::vec3(world[1]);
  camera.up = glm::length(up) > 0.0f ? glm::normalize(up) : glm::vec3(0.0f, 1.0f, 0.0f);
  camera.vertical_fov = float(lens.yfov);
  camera.near_plane = float(lens.znear);
  camera.far_plane = float(lens.zfar);  // 0: infinite, which the loader bounds by the scene
  return camera;
}

TextureTransform texture_transform(const tinygltf::ExtensionMap& extensions, int texcoord, const std::string& what,
                                   const std::filesystem::path& file) {
  TextureTransform transform;
  transform.texcoord = texcoord;
  const auto found = extensions.find("KHR_texture_transform");
  if (found == extensions.end()) return transform;
  const tinygltf::Value& value = found->second;
  transform.present = true;
  const glm::vec2 offset = vec2_or(value, "offset", glm::vec2(0.0f));
  const glm::vec2 scale = vec2_or(value, "scale", glm::vec2(1.0f));
  const float rotation = float(number_or(value, "rotation", 0.0));
  transform.texcoord = int(number_or(value, "texCoord", texcoord));
  if (!std::isfinite(offset.x) || !std::isfinite(offset.y) || !std::isfinite(scale.x) || !std::isfinite(scale.y) ||
      !std::isfinite(rotation) || transform.texcoord < 0)
    throw LoadError(file, what + ": KHR_texture_transform has a non-finite number or a negative texCoord");
  // Translation x rotation x scale, column-major as glm is. The rotation turns the UVs
  // clockwise as printed (u' = c u + s v, v' = -s u + c v): the README's GLSL reads the
  // other way, but Khronos' TextureTransformTest marks that direction as wrong, and
  // three.js turns UVs this way.
  const float c = std::cos(rotation), s = std::sin(rotation);
  const glm::mat3 translate(1, 0, 0, 0, 1, 0, offset.x, offset.y, 1);
  const glm::mat3 rotate(c, -s, 0, s, c, 0, 0, 0, 1);
  const glm::mat3 scaling(scale.x, 0, 0, 0, scale.y, 0, 0, 0, 1);
  transform.matrix = translate * rotate * scaling;
  return transform;
}

}  // namespace avsm::scene::detail
