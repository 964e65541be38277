#pragma once
// Values over time (seconds): the scene file's "animation" blocks (content/README.md,
// "Animation") and what they move. A Track holds keys and how to blend between them;
// before its first key and after its last it holds that key's value.
#include "scene/camera.h"
#include "scene/light.h"
#include "scene/mesh.h"

#include <glm/glm.hpp>
#include <glm/gtc/quaternion.hpp>

#include <algorithm>
#include <cstddef>
#include <memory>
#include <string_view>
#include <utility>
#include <vector>

namespace avsm::scene {

// step: each key's value until the next key. linear: straight between keys. cubic: a
// Hermite spline through the keys whose tangents are the neighbours' slope (Catmull-Rom
// for uneven key times), or the given ones (glTF's CUBICSPLINE).
enum class Interpolation { step, linear, cubic };
std::string_view to_string(Interpolation interpolation);

template <int N>
struct Track {
  using Value = glm::vec<N, float>;
  std::vector<float> times;  // strictly increasing
  std::vector<Value> values;  // one per time
  // Per key, in value units per second (glTF CUBICSPLINE); empty: Catmull-Rom.
  std::vector<Value> in_tangents, out_tangents;
  Interpolation interpolation = Interpolation::linear;

  bool empty() const { return times.empty(); }
  float end() const { return times.empty() ? 0.0f : times.back(); }
  Value sample(float time) const;
  Value sample_or(float time, const Value& rest) const { return empty() ? rest : sample(time); }
};

// A rotation track of unit quaternions (x, y, z, w): linear keys blend along the shortest
// arc (slerp), cubic ones are normalized after the spline.
glm::quat sample_rotation(const Track<4>& track, float time);

// A glTF file's node hierarchy and its animation channels (translation, rotation and scale;
// glTF's "weights" are morph targets, which are not supported). Node transforms exclude
// the placement the scene file puts the file at.
struct NodeAnimation {
  struct Node {
    int parent = -1;
    glm::mat4 matrix{1.0f};  // a node given by "matrix", which glTF does not let animations move
    bool has_matrix = false;
    glm::vec3 translation{0.0f}, scale{1.0f};
    glm::quat rotation{1.0f, 0.0f, 0.0f, 0.0f};
    Track<3> translation_track, scale_track;
    Track<4> rotation_track;
    bool animated() const { return !translation_track.empty() || !rotation_track.empty() || !scale_track.empty(); }
  };
  std::vector<Node> nodes;

  bool animated() const;
  float end() const;
  // Node `node`'s world transform at `time` (its parents' and its own tracks sampled),
  // or at rest (the file's node transforms, as the loader placed the meshes).
  glm::mat4 world(int node, float time) const { return world_of(node, &time); }
  glm::mat4 rest_world(int node) const { return world_of(node, nullptr); }

 private:
  glm::mat4 world_of(int node, const float* time) const;
};

// A placement as the scene file writes transforms, T * Rz * Ry * Rx * S, with any part
// animated; a part without a track keeps its rest value.
struct TransformTracks {
  glm::vec3 rest_translation{0.0f}, rest_rotation_deg{0.0f}, rest_scale{1.0f};
  Track<3> translation, rotation_deg, scale;

  bool empty() const { return translation.empty() && rotation_deg.empty() && scale.empty(); }
  float end() const;
  glm::mat4 at(float time) const;
  glm::mat4 rest() const { return at_parts(rest_translation, rest_rotation_deg, rest_scale); }
  static glm::mat4 at_parts(const glm::vec3& translation, const glm::vec3& rotation_deg, const glm::vec3& scale);
};

// A camera's keyed members; those without a track keep the camera's own.
struct CameraTracks {
  Track<3> position, target, up;
  Track<1> vertical_fov_deg;

  bool empty() const { return position.empty() && target.empty() && up.empty() && vertical_fov_deg.empty(); }
  float end() const;
  Camera at(const Camera& rest, float time) const;
};

// A light's keyed placement: its position, and where it points (a direction, or a target
// it aims at); those without a track keep the light's own.
struct LightTracks {
  Track<3> position, direction, target;

  bool empty() const { return position.empty() && direction.empty() && target.empty(); }
  float end() const;
  Light at(const Light& rest, float time) const;
};

struct Scene;

// Everything in a loaded scene that moves, and how to put it where it is at a time.
struct SceneAnimation {
  std::vector<std::pair<std::size_t, CameraTracks>> cameras;  // Scene::cameras index
  std::vector<std::pair<std::size_t, LightTracks>> lights;    // Scene::lights index
  // A model's meshes (Scene::meshes[first, first + rest.size())), moved by its placement
  // and its glTF file's node animation: rest holds them as loaded, at the placement's
  // rest transform and the nodes' rest transforms. The file's lights and cameras (scene
  // indices, with their nodes) move with them.
  struct MovingModel {
    std::size_t first = 0;
    std::vector<Mesh> rest;
    std::vector<int> mesh_nodes;  // per rest mesh, its glTF node
    TransformTracks placement;
    std::shared_ptr<const NodeAnimation> nodes;
    std::vector<std::pair<std::size_t, int>> lights, cameras;
    std::vector<float> camera_focus;  // per camera: how far ahead its target lies

    glm::mat4 fixed_placement{1.0f};  // where the scene file puts the model when its placement has no keys

    float end() const { return std::max(placement.end(), nodes ? nodes->end() : 0.0f); }
    // Every key's time, of the placement and the nodes: where a path may turn.
    std::vector<float> key_times() const;
    glm::mat4 rest_world(int node) const { return placement_rest() * nodes->rest_world(node); }
    glm::mat4 world(int node, float time) const {
      return (placement.empty() ? fixed_placement : placement.at(time)) * nodes->world(node, time);
    }
    glm::mat4 placement_rest() const { return placement.empty() ? fixed_placement : placement.rest(); }
  };
  std::vector<MovingModel> models;

  bool empty() const { return cameras.empty() && lights.empty() && models.empty(); }
  // The last key's time: a shot's natural length.
  float duration() const;
  // The scene's meshes and lights that move (Scene::meshes, Scene::lights indices), in order.
  std::vector<std::size_t> moving_meshes() const;
  std::vector<std::size_t> moving_lights() const;
  // Writes the animated cameras, lights and meshes as they are at `time` into `scene`
  // (built with this animation by load_scene: the indices are its).
  void pose(Scene& scene, float time) const;
  // Mesh `rest` moved from `rest_placement` to `placement`: positions, normals, tangents
  // and bounds.
  static Mesh moved(const Mesh& rest, const glm::mat4& rest_placement, const glm::mat4& placement);
};

}  // namespace avsm::scene
