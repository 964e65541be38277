#include "scene/scene.h"

#include <algorithm>
#include <cctype>
#include <cmath>

namespace avsm::scene {
namespace {

// An asset's LoadError names the asset file; add which scene entry asked for it.
template <class Load>
auto with_context(const SceneDescription& description, const std::string& entry_path, Load&& load) {
  try {
    return load();
  } catch (const LoadError& error) {
    throw LoadError(error.file(), error.problem() + " (referenced by " + description.file.string() + " at " +
                                      entry_path + ")");
  }
}

std::string lowercase_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return extension;
}

// The glTF file's KHR_lights_punctual lights join the scene's, named "<model>/<light>",
// with what the scene file's "lights" block changes or drops. Returns each joined light's
// scene index with its node.
std::vector<std::pair<std::size_t, int>> add_file_lights(Scene& scene, const ModelEntry& entry, std::vector<Light>& lights,
                                                         const std::vector<int>& nodes) {
  for (const GltfLightOverride& change : entry.light_overrides) {
    const auto light = std::find_if(lights.begin(), lights.end(), [&](const Light& l) { return l.name == change.name; });
    if (light == lights.end()) {
      std::string names;
      for (const Light& l : lights) names += " '" + l.name + "'";
      throw LoadError(entry.file, "has no KHR_lights_punctual light named '" + change.name + "' (lights:" +
                                      (names.empty() ? " none" : names) + "), which " + change.path + " names");
    }
    if (change.color) light->color = *change.color;
    if (change.intensity) light->intensity = *change.intensity;
    if (change.range) light->range = *change.range;
    if (change.shadow) light->shadow = *change.shadow;
    if (change.drop) light->name.clear();  // removed below, once every name has been found
  }
  std::vector<std::pair<std::size_t, int>> joined;
  if (!entry.file_lights) return joined;
  for (std::size_t i = 0; i < lights.size(); ++i) {
    if (lights[i].name.empty()) continue;
    lights[i].name = entry.name + "/" + lights[i].name;
    joined.emplace_back(scene.lights.size(), nodes[i]);
    scene.lights.push_back(std::move(lights[i]));
  }
  return joined;
}

// Adds the model's meshes, materials, textures, lights and cameras to the scene; when it
// moves (its placement is keyed, or its file's nodes are), adds what moves to the scene's
// animation.
void add_model(Scene& scene, const ModelEntry& entry, const std::string& where, GltfAsset asset) {
  SceneAnimation::MovingModel motion;
  motion.first = scene.meshes.size();
  motion.placement = entry.animation;
  motion.fixed_placement = entry.transform;
  motion.nodes = asset.nodes;
  motion.mesh_nodes = asset.mesh_nodes;
  const auto material_base = static_cast<std::uint32_t>(scene.materials.size());
  const auto texture_base = static_cast<int>(scene.textures.size());
  for (Material& material : asset.materials) {
    for (int* texture : material.textures())
      if (*texture >= 0) *texture += texture_base;
    scene.materials.push_back(std::move(material));
  }
  for (Texture& texture : asset.textures) scene.textures.push_back(std::move(texture));
  for (Mesh& mesh : asset.meshes) {
    mesh.material += material_base;
    mesh.name = entry.name + "/" + mesh.name;
    scene.meshes.push_back(std::move(mesh));
  }
  const std::string label = where + " (" + entry.file.filename().string() + "): ";
  if (asset.line_strands.strand_count() > 0)
    scene.warnings.push_back(label + std::to_string(asset.line_strands.strand_count()) +
                             " line strands ignored; list the file under \"hair\" to load them as strands");
  if (asset.point_primitives_skipped > 0)
    scene.warnings.push_back(label + std::to_string(asset.point_primitives_skipped) + " POINTS primitives ignored");
  for (const std::string& warning : asset.warnings) scene.warnings.push_back(label + "glTF: " + warning);
  motion.lights = add_file_lights(scene, entry, asset.lights, asset.light_nodes);
  for (std::size_t c = 0; c < asset.cameras.size(); ++c) {
    Camera& camera = asset.cameras[c];
    camera.name = entry.name + "/" + camera.name;
    motion.cameras.emplace_back(scene.cameras.size(), asset.camera_nodes[c]);
    motion.camera_focus.push_back(glm::length(camera.target - camera.position));
    scene.cameras.push_back(std::move(camera));
  }
  if (entry.animation.empty() && !(asset.nodes && asset.nodes->animated())) return;
  motion.rest.assign(scene.meshes.begin() + std::ptrdiff_t(motion.first), scene.meshes.end());
  scene.animation.models.push_back(std::move(motion));
}

HairGroom load_hair_file(const HairEntry& entry) {
  const std::string extension = lowercase_extension(entry.file);
  if (extension == ".gltf" || extension == ".glb") {
    GltfOptions options;
    options.transform = entry.transform;
    HairGroom groom = load_gltf(entry.file, options).line_strands;
    if (groom.strand_count() == 0)
      throw LoadError(entry.file, "has no LINES, LINE_LOOP or LINE_STRIP primitives to use as hair");
    return groom;
  }
  HairGroom groom = extension == ".tfx" ? load_tfx(entry.file) : load_cyhair(entry.file);
  transform_groom(groom, entry.transform);
  return groom;
}

// Final widths are world units: the entry's width (times the file's relative
// factors), or the file's absolute widths already scaled by the placement.
void apply_hair_overrides(HairGroom& groom, const HairEntry& entry) {
  if (entry.width) {
    for (float& width : groom.strand_width)
      width = groom.width_kind == StrandWidth::relative ? width * *entry.width : *entry.width;
  }
  groom.width_kind = StrandWidth::absolute;
  if (entry.opacity) std::fill(groom.strand_opacity.begin(), groom.strand_opacity.end(), *entry.opacity);
  if (entry.color) std::fill(groom.strand_color.begin(), groom.strand_color.end(), *entry.color);
  groom.name = entry.name;
}

// The scene's bounds grown to hold its moving meshes wherever they go: placed at every
// key (where a path turns) and at 256 instants between, the box they sweep then padded by
// 1% of its size for what a spline does between samples.
void extend_by_motion(Scene& scene) {
  constexpr int kSamples = 256;
  const float duration = scene.animation.duration();
  for (const SceneAnimation::MovingModel& model : scene.animation.models) {
    std::vector<float> times = model.key_times();
    for (int sample = 0; sample <= kSamples; ++sample) times.push_back(duration * float(sample) / kSamples);
    Bounds swept;
    for (float time : times)
      for (std::size_t i = 0; i < model.rest.size(); ++i) {
        const int node = model.mesh_nodes[i];
        const glm::mat4 rest = model.rest_world(node);
        if (!(std::abs(glm::determinant(glm::mat3(rest))) > 1e-20f)) continue;  // stays put (SceneAnimation::moved)
        swept.extend(transform_bounds(model.rest[i].bounds, model.world(node, time) * glm::inverse(rest)));
      }
    if (swept.empty()) continue;
    const glm::vec3 pad = 0.01f * swept.size();
    scene.bounds.extend(swept.min - pad);
    scene.bounds.extend(swept.max + pad);
  }
}

}  // namespace

Scene load_scene(const SceneDescription& description) {
  Scene scene;
  scene.file = description.file;
  scene.lights = description.lights;
  scene.cameras = description.cameras;
  scene.volume_shading = description.volume_shading;
  scene.shadows = description.shadows;
  scene.fog = description.fog;

  for (std::size_t i = 0; i < description.models.size(); ++i) {
    const ModelEntry& entry = description.models[i];
    const std::string where = "models[" + std::to_string(i) + "]";
    GltfOptions options;
    options.transform = entry.transform;
    options.missing_normals = entry.missing_normals;
    add_model(scene, entry, where, with_context(description, where, [&] { return load_gltf(entry.file, options); }));
  }
  // (A description built in code may leave the animations out.)
  for (std::size_t i = 0; i < std::min(description.lights.size(), description.light_animations.size()); ++i)
    if (!description.light_animations[i].empty()) scene.animation.lights.emplace_back(i, description.light_animations[i]);
  for (std::size_t i = 0; i < std::min(description.cameras.size(), description.camera_animations.size()); ++i)
    if (!description.camera_animations[i].empty()) scene.animation.cameras.emplace_back(i, description.camera_animations[i]);
  for (std::size_t i = 0; i < description.volumes.size(); ++i) {
    const VolumeEntry& entry = description.volumes[i];
    const std::string where = "volumes[" + std::to_string(i) + "]";
    const std::optional<FramePattern> pattern = parse_frame_pattern(entry.file);  // checked as the file was read
    if (!pattern) {
      scene.volumes.push_back(with_context(description, where, [&] { return load_volume(entry, entry.file); }));
      continue;
    }
    // A sequence: the frame at time 0 now, the others as they play (renderer/volume_sequence_player.h).
    VolumeSequence sequence = with_context(description, where, [&] { return open_volume_sequence(entry, *pattern, i); });
    scene.volumes.push_back(with_context(description, where, [&] { return sequence.load_frame(sequence.timing.frame_at(0.0f)); }));
    scene.volume_sequences.push_back(std::move(sequence));
  }
  for (std::size_t i = 0; i < description.hair.size(); ++i) {
    const HairEntry& entry = description.hair[i];
    const std::string where = "hair[" + std::to_string(i) + "]";
    HairGroom groom = with_context(description, where, [&] { return load_hair_file(entry); });
    apply_hair_overrides(groom, entry);
    scene.hair.push_back(std::move(groom));
  }

  if (scene.cameras.empty())
    throw LoadError(description.file, "cameras: a scene needs at least one camera, and its models' glTF files have none");
  for (const Mesh& mesh : scene.meshes) scene.bounds.extend(mesh.bounds);
  for (const HairGroom& groom : scene.hair) scene.bounds.extend(groom.bounds);
  for (const Volume& volume : scene.volumes) scene.bounds.extend(volume.world_bounds);
  for (const VolumeSequence& sequence : scene.volume_sequences) scene.bounds.extend(sequence.bounds);
  extend_by_motion(scene);
  return scene;
}

float Scene::duration() const {
  float end = animation.duration();
  for (const VolumeSequence& sequence : volume_sequences)  // the last frame, shown for one frame's time
    end = std::max(end, float(sequence.timing.last - sequence.timing.offset + 1) / sequence.timing.fps);
  return end;
}

Scene load_scene(const std::filesystem::path& file) { return load_scene(read_scene_description(file)); }

}  // namespace avsm::scene
