#pragma once
// A loaded scene: every asset read, placed in one world space (metres by
// convention, +Y up) and checked. Start here: load_scene(path).
#include "scene/animation.h"
#include "scene/bounds.h"
#include "scene/camera.h"
#include "scene/description.h"
#include "scene/gltf.h"
#include "scene/hair.h"
#include "scene/light.h"
#include "scene/load_error.h"
#include "scene/mesh.h"
#include "scene/volume.h"
#include "scene/volume_sequence.h"

#include <filesystem>
#include <string>
#include <vector>

namespace avsm::scene {

struct Scene {
  std::filesystem::path file;
  std::vector<Mesh> meshes;         // world space; opaque ones cast into shadow maps as blockers
  std::vector<Material> materials;  // Mesh::material indexes this
  std::vector<Texture> textures;    // the Material texture members index this
  std::vector<HairGroom> hair;      // world space, StrandWidth::absolute (world units)
  std::vector<Volume> volumes;      // a sequence's holds the frame shown at time 0
  std::vector<VolumeSequence> volume_sequences;  // the volumes whose frames change over time
  std::vector<Light> lights;
  std::vector<Camera> cameras;      // at least one
  VolumeShading volume_shading;     // how the camera sees the volumes
  SceneShadows shadows;             // the budget and switches all maps share
  Fog fog;                          // the medium outside the volumes (none unless the file has one)
  // meshes, hair and volume bounds together; with moving meshes, everywhere they go
  // (sampled over the animation), so that maps fitted once hold the whole shot
  Bounds bounds;
  SceneAnimation animation;         // what moves; pose(*this, t) puts it where it is at t
  std::vector<std::string> warnings;  // things that loaded but deserve a log line

  // Something changes over time: keyed or glTF animation, or a volume sequence.
  bool moves() const { return !animation.empty() || !volume_sequences.empty(); }
  // When the last key or sequence frame is reached: a shot's natural length, in seconds.
  float duration() const;
};

// Reads the scene file and every asset it references. Throws LoadError: for
// the scene file itself the message names it and the JSON path; for an asset
// it names the asset file, the problem, and the scene entry that referenced it.
Scene load_scene(const std::filesystem::path& file);
Scene load_scene(const SceneDescription& description);

}  // namespace avsm::scene
