#pragma once
// glTF 2.0 (.gltf with .bin / data URIs, and .glb) through tinygltf.
#include "scene/animation.h"
#include "scene/camera.h"
#include "scene/hair.h"
#include "scene/light.h"
#include "scene/mesh.h"

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>
#include <filesystem>
#include <memory>
#include <span>
#include <string>
#include <vector>

namespace avsm::scene {

struct GltfOptions {
  glm::mat4 transform{1.0f};  // applied on top of the node hierarchy
  NormalGeneration missing_normals = NormalGeneration::flat;
  // Read external buffers and images (.bin, .png) next to the file. Off for the
  // fuzzer, so that fuzz input cannot make the loader read arbitrary files.
  bool allow_external_files = true;
  std::uint64_t max_file_bytes = 1ull << 31;  // per file read (the glTF, each .bin, each image)
  std::uint32_t max_texture_size = 16384;     // per side, checked before decoding
  // Cap on vertices produced in total: node instancing multiplies mesh sizes,
  // so a small file could otherwise ask for unbounded memory.
  std::uint64_t max_vertices = 1ull << 27;
};

struct GltfAsset {
  std::vector<Mesh> meshes;          // one per triangle primitive per node that uses it
  std::vector<Material> materials;   // Mesh::material indexes this
  std::vector<Texture> textures;     // the Material texture members index this
  // LINES, LINE_STRIP and LINE_LOOP primitives as strands (StrandWidth::relative,
  // width 1, opacity 1, colour = the material's base colour). Consecutive LINES
  // segments that share an index are joined into one strand. Empty when none.
  HairGroom line_strands;
  std::size_t point_primitives_skipped = 0;  // POINTS primitives have no use here
  // KHR_lights_punctual lights and perspective cameras, where the nodes place them
  // (gltf_extensions.h: names, units, how a camera's target and infinite far plane are set).
  // Lights get the default shadow settings.
  std::vector<Light> lights;
  std::vector<Camera> cameras;
  // The node hierarchy with the file's animation channels (all animations play together),
  // and the node that placed each mesh, light and camera above: what moves them.
  std::shared_ptr<NodeAnimation> nodes;
  std::vector<int> mesh_nodes, light_nodes, camera_nodes;
  std::vector<std::string> warnings;         // tinygltf's warnings, for logs
  Bounds bounds;                             // of the meshes and the strands
};

// Loads the default scene (or scene 0, or every root node when there are no
// scenes). Throws LoadError naming the file for anything malformed: bad JSON or
// GLB chunks, missing buffers or images, accessors out of their buffers, indices
// out of range, non-finite positions, node cycles, unsupported required
// extensions (e.g. Draco), undecodable textures, non-finite
// normals. Zero-length normals (a known exporter bug) are replaced by smooth
// normals at those vertices, with a warning. Read: KHR_lights_punctual,
// KHR_texture_transform (baked into the UVs), KHR_mesh_quantization,
// KHR_materials_emissive_strength. Other extensions used but not required, skins,
// morph targets and animations each get a warning saying what is left out.
GltfAsset load_gltf(const std::filesystem::path& file, const GltfOptions& options = {});
// Same from memory; `name` is used in messages and its folder for external files.
GltfAsset parse_gltf(std::span<const std::byte> bytes, const std::filesystem::path& name,
                     const GltfOptions& options = {});

}  // namespace avsm::scene
