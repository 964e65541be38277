#pragma once
// What a glTF file carries besides its meshes and materials, and the extensions it
// uses: KHR_lights_punctual lights and cameras placed by nodes, KHR_texture_transform,
// and a warning for each extension that is used but not supported. Internal to the
// glTF loader (gltf.cpp); each function throws LoadError naming `file` on bad input.
#include "scene/camera.h"
#include "scene/light.h"

#include <tiny_gltf.h>

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace avsm::scene::detail {

// Extensions the loader reads: a file may require them.
bool is_supported_gltf_extension(const std::string& extension);
// One line per extension in extensionsUsed that the loader does not read, naming what
// of the file is ignored (it is loaded without it), plus skins (shown in their bind
// pose), morph targets (shown without them) and several animations (played together).
std::vector<std::string> ignored_content_warnings(const tinygltf::Model& model, const std::filesystem::path& file);

// The KHR_lights_punctual light a node places (nullopt when it places none), at the
// node's world transform: it shines along the node's -Z. Photometric units become the
// renderer's: a white Lambertian surface lit by E lux reflects E / pi (cd and lux / pi).
// Named after the node, else the light, else "light <index>".
std::optional<Light> node_light(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                                const std::filesystem::path& file);

// The perspective camera a node places (nullopt when it places none; an orthographic
// one is left out with a warning in `warnings`). It looks down the node's -Z with +Y up;
// its target is `focus_distance` ahead (the orbit's centre). An infinite far plane
// becomes `infinite_far`. Named after the node, else the camera, else "camera <index>".
std::optional<Camera> node_camera(const tinygltf::Model& model, const tinygltf::Node& node, const glm::mat4& world,
                                  const std::filesystem::path& file, std::vector<std::string>& warnings);

// A texture's KHR_texture_transform as a 3x3 UV matrix (identity without one), and the
// UV set it reads (its texCoord override, else `texcoord`).
struct TextureTransform {
  glm::mat3 matrix{1.0f};
  int texcoord = 0;
  bool present = false;
};
TextureTransform texture_transform(const tinygltf::ExtensionMap& extensions, int texcoord, const std::string& what,
                                   const std::filesystem::path& file);

}  // namespace avsm::scene::detail
