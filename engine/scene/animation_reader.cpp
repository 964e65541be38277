#include "scene/animation_reader.h"

#include <cmath>
#include <string>

namespace avsm::scene::detail {
namespace {

using json = nlohmann::json;

template <int N>
glm::vec<N, float> read_value(const Reader& reader, const json& value, const std::string& path) {
  if constexpr (N == 1) {
    return glm::vec<1, float>(float(reader.number(value, path)));
  } else {
    return reader.vec3(value, path);
  }
}

// {"keys": [[time, value], ...], "interpolation": "step" | "linear" | "cubic"}
template <int N>
Track<N> read_track(const Reader& reader, const json& value, const std::string& path) {
  ObjectReader object(reader, value, path);
  Track<N> track;
  track.interpolation = choice<Interpolation>(object, "interpolation", Interpolation::linear,
                                              {{"step", Interpolation::step}, {"linear", Interpolation::linear}, {"cubic", Interpolation::cubic}});
  const json& keys = object.required("keys");
  const std::string keys_path = object.path_of("keys");
  reader.expect(keys.is_array() && !keys.empty(), keys_path, "expected a non-empty array of [time, value] keys");
  for (std::size_t i = 0; i < keys.size(); ++i) {
    const std::string key_path = index_path(keys_path, i);
    reader.expect(keys[i].is_array() && keys[i].size() == 2, key_path,
                  std::string("expected [time, value], the value ") + (N == 1 ? "a number" : "3 numbers"));
    const float time = float(reader.number(keys[i][0], index_path(key_path, 0)));
    reader.expect(track.times.empty() || time > track.times.back(), index_path(key_path, 0),
                  "key times must increase (this key's is not after the one before)");
    track.times.push_back(time);
    track.values.push_back(read_value<N>(reader, keys[i][1], index_path(key_path, 1)));
  }
  object.finish();
  return track;
}

// The "animation" object of `entry`, its members read by `read_member(name, json, path)`;
// an empty object is an error (it says nothing).
template <class ReadMember>
void read_animation_block(ObjectReader& entry, ReadMember&& read_member) {
  const json* block = entry.optional("animation");
  if (block == nullptr) return;
  ObjectReader animation(entry.reader(), *block, entry.path_of("animation"));
  entry.reader().expect(block->is_object() && !block->empty(), entry.path_of("animation"),
                        "expected an object of keyed members");
  read_member(animation);
  animation.finish();
}

}  // namespace

CameraTracks read_camera_animation(ObjectReader& camera) {
  CameraTracks tracks;
  read_animation_block(camera, [&](ObjectReader& animation) {
    const Reader& reader = animation.reader();
    if (const json* v = animation.optional("position")) tracks.position = read_track<3>(reader, *v, animation.path_of("position"));
    if (const json* v = animation.optional("target")) tracks.target = read_track<3>(reader, *v, animation.path_of("target"));
    if (const json* v = animation.optional("up")) tracks.up = read_track<3>(reader, *v, animation.path_of("up"));
    if (const json* v = animation.optional("vertical_fov_deg")) {
      tracks.vertical_fov_deg = read_track<1>(reader, *v, animation.path_of("vertical_fov_deg"));
      for (const glm::vec<1, float>& fov : tracks.vertical_fov_deg.values)
        animation.check(fov.x > 0.0f && fov.x < 180.0f, "vertical_fov_deg", "every key must be between 0 and 180");
    }
  });
  return tracks;
}

LightTracks read_light_animation(ObjectReader& entry, const Light& light) {
  LightTracks tracks;
  read_animation_block(entry, [&](ObjectReader& animation) {
    const Reader& reader = animation.reader();
    const bool positioned = light.type != LightType::directional;
    const bool pointed = light.type != LightType::point && light.type != LightType::sphere;
    animation.check(positioned || !animation.has("position"), "position", "a directional light has no position");
    for (const char* key : {"direction", "target"})
      animation.check(pointed || !animation.has(key), key, "a " + std::string(to_string(light.type)) + " light shines every way");
    animation.check(!(animation.has("direction") && animation.has("target")), "target", "give 'direction' or 'target', not both");
    animation.check(light.type != LightType::directional || !animation.has("target"), "target",
                    "a directional light has no position to aim from; key its 'direction'");
    if (const json* v = animation.optional("position")) tracks.position = read_track<3>(reader, *v, animation.path_of("position"));
    if (const json* v = animation.optional("direction")) tracks.direction = read_track<3>(reader, *v, animation.path_of("direction"));
    if (const json* v = animation.optional("target")) tracks.target = read_track<3>(reader, *v, animation.path_of("target"));
  });
  // Aimed at a fixed point while moving: the point stays its aim.
  if (!tracks.position.empty() && tracks.direction.empty() && tracks.target.empty() && entry.has("target")) {
    tracks.target.times = {0.0f};
    tracks.target.values = {entry.vec3("target")};
  }
  return tracks;
}

TransformTracks read_model_animation(ObjectReader& model) {
  TransformTracks tracks;
  if (!model.has("animation")) return tracks;
  if (const json* transform = model.optional("transform")) {
    const Reader& reader = model.reader();
    const std::string path = model.path_of("transform");
    reader.expect(transform->is_object() && !transform->contains("matrix"), path,
                  "an animated model's transform must be translation / rotation_deg / scale, not a matrix");
    if (transform->contains("translation")) tracks.rest_translation = reader.vec3((*transform)["translation"], child_path(path, "translation"));
    if (transform->contains("rotation_deg")) tracks.rest_rotation_deg = reader.vec3((*transform)["rotation_deg"], child_path(path, "rotation_deg"));
    if (transform->contains("scale")) {
      const json& s = (*transform)["scale"];
      tracks.rest_scale = s.is_number() ? glm::vec3(float(reader.number(s, child_path(path, "scale")))) : reader.vec3(s, child_path(path, "scale"));
    }
  }
  read_animation_block(model, [&](ObjectReader& animation) {
    const Reader& reader = animation.reader();
    if (const json* v = animation.optional("translation")) tracks.translation = read_track<3>(reader, *v, animation.path_of("translation"));
    if (const json* v = animation.optional("rotation_deg")) tracks.rotation_deg = read_track<3>(reader, *v, animation.path_of("rotation_deg"));
    if (const json* v = animation.optional("scale")) {
      tracks.scale = read_track<3>(reader, *v, animation.path_of("scale"));
      for (const glm::vec3& s : tracks.scale.values)
        animation.check(s.x != 0.0f && s.y != 0.0f && s.z != 0.0f, "scale", "a key of scale 0 makes the transform singular");
    }
  });
  return tracks;
}

}  // namespace avsm::scene::detail
