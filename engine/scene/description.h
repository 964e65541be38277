#pragma once
// The scene file (JSON) as parsed and checked, before any asset is read. The
// format is documented in content/README.md. Parsing is strict: unknown keys,
// duplicate keys, wrong types and out-of-range values are LoadErrors whose
// message names the file, the JSON path (e.g. "lights[1].shadow.nodes") and
// the problem.
#include "scene/animation.h"
#include "scene/camera.h"
#include "scene/fog.h"
#include "scene/light.h"
#include "scene/mesh.h"
#include "scene/volume.h"

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

namespace avsm::scene {

inline constexpr int kSceneFormatVersion = 1;

// "models[i].lights.<name>": what the scene file changes about one of a glTF file's
// KHR_lights_punctual lights (named as GltfAsset::lights names them).
struct GltfLightOverride {
  std::string name;
  std::string path;  // its JSON path, for "the file has no such light"
  bool drop = false;  // "off"
  std::optional<glm::vec3> color;
  std::optional<float> intensity;
  std::optional<float> range;
  std::optional<ShadowSettings> shadow;
};

struct ModelEntry {  // "models": glTF files whose triangles become meshes
  std::string name;
  std::filesystem::path file;  // absolute or relative to the scene file, resolved
  glm::mat4 transform{1.0f};
  NormalGeneration missing_normals = NormalGeneration::flat;
  bool file_lights = true;  // "lights": "off" leaves out all of the file's lights
  std::vector<GltfLightOverride> light_overrides;
  TransformTracks animation;  // "animation": its placement over time (empty: it stays)
};

// A volume sequence's timing as the scene file gives it ("sequence": {...}); unset
// values come from the files on disk (scene/volume_sequence.h).
struct SequenceSettings {
  std::optional<int> first, last;  // "frames": [first, last], file frame numbers
  float fps = 24.0f;               // "fps"
  std::optional<int> offset;       // "offset": the file frame shown at time 0 (default: the first)
  bool loop = false;               // "mode": "hold" (default) or "loop"
};

struct VolumeEntry {  // "volumes": OpenVDB fog volumes
  std::string name;
  std::filesystem::path file;  // a frame pattern ("smoke.####.vdb", "$F4", "%04d") makes it a sequence
  SequenceSettings sequence;
  std::string grid;
  glm::mat4 transform{1.0f};
  float extinction_scale = 1.0f;  // sigma_t = extinction_scale * density, per world unit
  glm::vec3 albedo{1.0f};
  int majorant_brick_size = 8;
  float lighting_cache_downsample = 2.0f;  // "lighting_cache": {"downsample": N}
  bool lighting_cache = true;              // "lighting_cache": "off" clears it
  MultipleScattering multiple_scattering;  // "multiple_scattering": "off" or {"octaves", "attenuation", "contribution"}
  float sky_light = 1.0f;                  // "sky_light": the sky's share, 0 to 4
};

struct HairEntry {  // "hair": .tfx, .hair, or the line primitives of a .gltf/.glb
  std::string name;
  std::filesystem::path file;
  glm::mat4 transform{1.0f};
  std::optional<float> width;        // world units; see HairGroom / content/README.md
  std::optional<float> opacity;      // overrides the file's per-strand values
  std::optional<glm::vec3> color;
};

struct SceneDescription {
  std::filesystem::path file;
  std::string description;
  std::vector<ModelEntry> models;
  std::vector<VolumeEntry> volumes;
  std::vector<HairEntry> hair;
  std::vector<Light> lights;
  std::vector<Camera> cameras;  // at least one (or the models' glTF cameras)
  // "animation" of each light and camera, parallel to `lights` and `cameras` (empty: it stays).
  std::vector<LightTracks> light_animations;
  std::vector<CameraTracks> camera_animations;
  VolumeShading volume_shading;  // "volume_shading"
  SceneShadows shadows;          // "shadows"
  Fog fog;                       // "fog" (scene/fog.h)
};

class ObjectReader;  // scene/json_reader.h
// The shadow keys a light's "shadow" block shares with a sweep manifest's shadow
// overrides (technique, nodes, resolution, filter, kernel, kernel_radius, sort, build,
// fit, cascades, clusters, parameters), each checked; only those present are set. With
// `with_light_keys` (a manifest's), also the light's own keys a sweep varies (virtual_lights).
ShadowOverrides read_shadow_overrides(ObjectReader& object, bool with_light_keys = false);

// Reads and checks a scene file; asset paths come back resolved against its folder.
SceneDescription read_scene_description(const std::filesystem::path& file);
// The same from text; `file` names the scene in messages and anchors relative paths.
SceneDescription parse_scene_description(std::string_view json_text, const std::filesystem::path& file);

}  // namespace avsm::scene
