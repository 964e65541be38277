#include "scene/animation.h"

#include "scene/scene.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>

namespace avsm::scene {

std::string_view to_string(Interpolation interpolation) {
  switch (interpolation) {
    case Interpolation::step: return "step";
    case Interpolation::linear: return "linear";
    case Interpolation::cubic: return "cubic";
  }
  return "?";
}

template <int N>
typename Track<N>::Value Track<N>::sample(float time) const {
  if (times.empty()) return Value(0.0f);
  if (!(time > times.front())) return values.front();  // NaN holds the first key too
  if (time >= times.back()) return values.back();
  const std::size_t k = std::size_t(std::upper_bound(times.begin(), times.end(), time) - times.begin()) - 1;
  if (interpolation == Interpolation::step) return values[k];
  const float span = times[k + 1] - times[k];
  const float s = (time - times[k]) / span;
  if (interpolation == Interpolation::linear) return glm::mix(values[k], values[k + 1], s);
  // Hermite: tangents in value units per second, scaled by the span.
  auto slope = [&](std::size_t i) {  // Catmull-Rom's: the neighbours' (one-sided at the ends)
    const std::size_t before = i > 0 ? i - 1 : i, after = i + 1 < times.size() ? i + 1 : i;
    return (values[after] - values[before]) / (times[after] - times[before]);
  };
  const Value m0 = out_tangents.empty() ? slope(k) : out_tangents[k];
  const Value m1 = in_tangents.empty() ? slope(k + 1) : in_tangents[k + 1];
  const float s2 = s * s, s3 = s2 * s;
  return (2 * s3 - 3 * s2 + 1) * values[k] + (s3 - 2 * s2 + s) * span * m0 + (-2 * s3 + 3 * s2) * values[k + 1] +
         (s3 - s2) * span * m1;
}

template struct Track<1>;
template struct Track<3>;
template struct Track<4>;

glm::quat sample_rotation(const Track<4>& track, float time) {
  auto quat = [](const glm::vec4& v) { return glm::quat(v.w, v.x, v.y, v.z); };
  if (track.empty()) return glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
  if (track.interpolation == Interpolation::linear && time > track.times.front() && time < track.times.back()) {
    const std::size_t k = std::size_t(std::upper_bound(track.times.begin(), track.times.end(), time) - track.times.begin()) - 1;
    const float s = (time - track.times[k]) / (track.times[k + 1] - track.times[k]);
    return glm::normalize(glm::slerp(quat(track.values[k]), quat(track.values[k + 1]), s));  // glm takes the shorter arc
  }
  const glm::vec4 v = track.sample(time);  // step, cubic (glTF: the spline, then normalized), or a held end
  const float length = glm::length(v);
  return length > 0.0f ? quat(v / length) : glm::quat(1.0f, 0.0f, 0.0f, 0.0f);
}

bool NodeAnimation::animated() const {
  return std::any_of(nodes.begin(), nodes.end(), [](const Node& n) { return n.animated(); });
}

float NodeAnimation::end() const {
  float end = 0.0f;
  for (const Node& n : nodes) end = std::max({end, n.translation_track.end(), n.rotation_track.end(), n.scale_track.end()});
  return end;
}

glm::mat4 NodeAnimation::world_of(int node, const float* time) const {
  glm::mat4 world(1.0f);
  for (int n = node; n >= 0; n = nodes[std::size_t(n)].parent) {  // the loader checked it is a forest
    const Node& at = nodes[std::size_t(n)];
    glm::mat4 local = at.matrix;
    if (!at.has_matrix) {
      const glm::vec3 t = time ? at.translation_track.sample_or(*time, at.translation) : at.translation;
      const glm::quat r = time && !at.rotation_track.empty() ? sample_rotation(at.rotation_track, *time) : at.rotation;
      const glm::vec3 s = time ? at.scale_track.sample_or(*time, at.scale) : at.scale;
      local = glm::translate(glm::mat4(1.0f), t) * glm::mat4_cast(r) * glm::scale(glm::mat4(1.0f), s);
    }
    world = local * world;
  }
  return world;
}

float TransformTracks::end() const { return std::max({translation.end(), rotation_deg.end(), scale.end()}); }

glm::mat4 TransformTracks::at_parts(const glm::vec3& translation, const glm::vec3& rotation_deg, const glm::vec3& scale) {
  const glm::vec3 r = glm::radians(rotation_deg);
  const glm::mat4 identity(1.0f);
  return glm::translate(identity, translation) * glm::rotate(identity, r.z, glm::vec3(0, 0, 1)) *
         glm::rotate(identity, r.y, glm::vec3(0, 1, 0)) * glm::rotate(identity, r.x, glm::vec3(1, 0, 0)) *
         glm::scale(identity, scale);
}

glm::mat4 TransformTracks::at(float time) const {
  return at_parts(translation.sample_or(time, rest_translation), rotation_deg.sample_or(time, rest_rotation_deg),
                  scale.sample_or(time, rest_scale));
}

float CameraTracks::end() const { return std::max({position.end(), target.end(), up.end(), vertical_fov_deg.end()}); }

Camera CameraTracks::at(const Camera& rest, float time) const {
  Camera camera = rest;
  camera.position = position.sample_or(time, rest.position);
  camera.target = target.sample_or(time, rest.target);
  camera.up = up.sample_or(time, rest.up);
  if (!vertical_fov_deg.empty()) camera.vertical_fov = glm::radians(vertical_fov_deg.sample(time).x);
  return camera;
}

float LightTracks::end() const { return std::max({position.end(), direction.end(), target.end()}); }

Light LightTracks::at(const Light& rest, float time) const {
  Light light = rest;
  light.position = position.sample_or(time, rest.position);
  glm::vec3 towards = rest.direction;
  if (!direction.empty()) towards = direction.sample(time);
  if (!target.empty()) towards = target.sample(time) - light.position;
  // A key path through zero (or a target reaching the light) keeps the rest direction.
  if (glm::length(towards) > 1e-6f) light.direction = glm::normalize(towards);
  return light;
}

float SceneAnimation::duration() const {
  float end = 0.0f;
  for (const auto& [index, tracks] : cameras) end = std::max(end, tracks.end());
  for (const auto& [index, tracks] : lights) end = std::max(end, tracks.end());
  for (const MovingModel& model : models) end = std::max(end, model.end());
  return end;
}

std::vector<std::size_t> SceneAnimation::moving_meshes() const {
  std::vector<std::size_t> meshes;
  for (const MovingModel& model : models)
    for (std::size_t i = 0; i < model.rest.size(); ++i) meshes.push_back(model.first + i);
  return meshes;
}

std::vector<float> SceneAnimation::MovingModel::key_times() const {
  std::vector<float> times;
  for (const Track<3>* track : {&placement.translation, &placement.rotation_deg, &placement.scale})
    times.insert(times.end(), track->times.begin(), track->times.end());
  if (nodes)
    for (const NodeAnimation::Node& node : nodes->nodes) {
      times.insert(times.end(), node.translation_track.times.begin(), node.translation_track.times.end());
      times.insert(times.end(), node.rotation_track.times.begin(), node.rotation_track.times.end());
      times.insert(times.end(), node.scale_track.times.begin(), node.scale_track.times.end());
    }
  return times;
}

std::vector<std::size_t> SceneAnimation::moving_lights() const {
  std::vector<std::size_t> moving;
  for (const auto& [index, tracks] : lights) moving.push_back(index);
  for (const MovingModel& model : models)
    for (const auto& [index, node] : model.lights) moving.push_back(index);
  std::sort(moving.begin(), moving.end());
  return moving;
}

Mesh SceneAnimation::moved(const Mesh& rest, const glm::mat4& rest_placement, const glm::mat4& placement) {
  // A mesh placed at rest by a singular transform (a node scaled to 0) has lost its
  // shape; it stays as it is (SceneAnimation's users are told at load).
  if (!(std::abs(glm::determinant(glm::mat3(rest_placement))) > 1e-20f)) return rest;
  const glm::mat4 delta = placement * glm::inverse(rest_placement);
  const glm::mat3 linear(delta);
  const glm::mat3 normal_matrix = glm::transpose(glm::inverse(linear));
  Mesh mesh = rest;
  mesh.bounds = Bounds{};
  for (glm::vec3& p : mesh.positions) {
    p = glm::vec3(delta * glm::vec4(p, 1.0f));
    mesh.bounds.extend(p);
  }
  for (glm::vec3& n : mesh.normals) n = glm::normalize(normal_matrix * n);
  for (glm::vec4& t : mesh.tangents) t = glm::vec4(glm::normalize(linear * glm::vec3(t)), t.w);
  return mesh;
}

void SceneAnimation::pose(Scene& scene, float time) const {
  for (const auto& [index, tracks] : cameras) scene.cameras[index] = tracks.at(scene.cameras[index], time);
  for (const auto& [index, tracks] : lights) scene.lights[index] = tracks.at(scene.lights[index], time);
  for (const MovingModel& model : models) {
    for (std::size_t i = 0; i < model.rest.size(); ++i) {
      const int node = model.mesh_nodes[i];
      scene.meshes[model.first + i] = moved(model.rest[i], model.rest_world(node), model.world(node, time));
    }
    for (const auto& [index, node] : model.lights) {  // glTF lights shine along their node's -Z
      const glm::mat4 world = model.world(node, time);
      scene.lights[index].position = glm::vec3(world[3]);
      if (glm::length(glm::vec3(world[2])) > 0.0f) scene.lights[index].direction = glm::normalize(-glm::vec3(world[2]));
    }
    for (std::size_t c = 0; c < model.cameras.size(); ++c) {  // and cameras look along it, +Y up
      const auto [index, node] = model.cameras[c];
      const glm::mat4 world = model.world(node, time);
      Camera& camera = scene.cameras[index];
      const glm::vec3 forward = -glm::vec3(world[2]), up = glm::vec3(world[1]);
      if (glm::length(forward) == 0.0f || glm::length(up) == 0.0f) continue;  // scaled to nothing: left where it was
      camera.position = glm::vec3(world[3]);
      camera.target = camera.position + glm::normalize(forward) * model.camera_focus[c];
      camera.up = glm::normalize(up);
    }
  }
}

}  // namespace avsm::scene
