// Strict reading of scene files. Every value goes through a reader that knows
// its JSON path, so every message can say exactly where the problem is.
#include "scene/description.h"

#include "scene/animation_reader.h"
#include "scene/binary_reader.h"
#include "scene/frame_pattern.h"
#include "scene/json_reader.h"
#include "scene/load_error.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>

namespace avsm::scene {
namespace {

using json = nlohmann::json;

constexpr std::uint64_t kMaxSceneFileBytes = 64ull << 20;

// ---- pieces ----

glm::mat4 read_matrix(const Reader& reader, const json& value, const std::string& path) {
  reader.expect(value.is_array() && value.size() == 16, path, "expected an array of 16 numbers (column-major)");
  glm::mat4 m;
  for (int i = 0; i < 16; ++i) m[i / 4][i % 4] = float(reader.number(value[i], index_path(path, i)));
  reader.expect(m[0][3] == 0.0f && m[1][3] == 0.0f && m[2][3] == 0.0f && m[3][3] == 1.0f, path,
                "not an affine transform (elements 3, 7, 11 must be 0 and element 15 must be 1)");
  return m;
}

// {"translation": [x,y,z], "rotation_deg": [x,y,z], "scale": s or [x,y,z]} -> T * Rz * Ry * Rx * S,
// or {"matrix": [16 numbers, column-major]}.
glm::mat4 read_transform(const Reader& reader, const json& value, const std::string& path) {
  ObjectReader object(reader, value, path);
  glm::mat4 result(1.0f);
  if (const json* matrix = object.optional("matrix")) {
    for (const char* other : {"translation", "rotation_deg", "scale"})
      object.check(!object.has(other), other, "cannot be combined with 'matrix'");
    result = read_matrix(reader, *matrix, object.path_of("matrix"));
  } else {
    const glm::vec3 translation = object.vec3_or("translation", glm::vec3(0.0f));
    const glm::vec3 rotation = object.vec3_or("rotation_deg", glm::vec3(0.0f));
    glm::vec3 scale(1.0f);
    if (const json* s = object.optional("scale"))
      scale = s->is_number() ? glm::vec3(float(reader.number(*s, object.path_of("scale"))))
                             : reader.vec3(*s, object.path_of("scale"));
    result = TransformTracks::at_parts(translation, rotation, scale);  // the form animations key too
  }
  object.finish();
  const float det = glm::determinant(glm::mat3(result));
  reader.expect(std::isfinite(det) && std::abs(det) > 1e-20f, path, "transform is singular (a scale of 0?)");
  return result;
}

glm::mat4 transform_or_identity(ObjectReader& object) {
  const json* value = object.optional("transform");
  return value ? read_transform(object.reader(), *value, object.path_of("transform")) : glm::mat4(1.0f);
}

std::filesystem::path asset_path(ObjectReader& object, const std::filesystem::path& scene_dir) {
  const std::string text = object.string("file");
  object.check(!text.empty(), "file", "must not be empty");
  std::filesystem::path path(text);
  if (path.is_relative()) path = scene_dir / path;
  return path.lexically_normal();
}

std::string name_or(ObjectReader& object, const std::string& fallback) {
  const std::string name = object.string_or("name", fallback);
  object.check(!name.empty(), "name", "must not be empty");
  return name;
}

ShadowSettings read_shadow(const Reader& reader, const json& value, const std::string& path);

// "lights": "off", or an object naming the file's lights, each "off" or an object of
// the light keys a scene may change about it (its place and type are the file's).
void read_gltf_light_overrides(ObjectReader& object, ModelEntry& entry) {
  const json* block = object.optional("lights");
  if (!block) return;
  const std::string path = object.path_of("lights");
  if (block->is_string()) {
    object.check(*block == "off", "lights", "must be \"off\" or an object of the file's lights by name");
    entry.file_lights = false;
    return;
  }
  object.check(block->is_object(), "lights", "must be \"off\" or an object of the file's lights by name");
  for (const auto& [name, value] : block->items()) {
    GltfLightOverride light;
    light.name = name;
    light.path = child_path(path, name);
    if (value.is_string()) {
      object.reader().expect(value == "off", light.path, "must be \"off\" or an object (color, intensity, range, shadow)");
      light.drop = true;
    } else {
      ObjectReader reader(object.reader(), value, light.path);
      light.color = reader.optional_vec3("color");
      reader.check(!light.color || glm::all(glm::greaterThanEqual(*light.color, glm::vec3(0.0f))), "color", "components must be >= 0");
      light.intensity = reader.optional_number("intensity");
      reader.check(!light.intensity || *light.intensity >= 0.0f, "intensity", "must be >= 0");
      light.range = reader.optional_number("range");
      reader.check(!light.range || *light.range >= 0.0f, "range", "must be >= 0 (0: no limit)");
      if (const json* shadow = reader.optional("shadow")) light.shadow = read_shadow(reader.reader(), *shadow, reader.path_of("shadow"));
      reader.finish();
    }
    entry.light_overrides.push_back(std::move(light));
  }
}

ModelEntry read_model(ObjectReader& object, const std::filesystem::path& scene_dir) {
  ModelEntry entry;
  entry.file = asset_path(object, scene_dir);
  entry.name = name_or(object, entry.file.stem().string());
  entry.transform = transform_or_identity(object);
  entry.missing_normals = choice<NormalGeneration>(object, "missing_normals", NormalGeneration::flat,
                                                   {{"flat", NormalGeneration::flat}, {"smooth", NormalGeneration::smooth}});
  read_gltf_light_overrides(object, entry);
  entry.animation = detail::read_model_animation(object);
  return entry;
}

// "multiple_scattering": "off" (single scattering) or {"octaves", "attenuation", "contribution"}.
MultipleScattering read_multiple_scattering(ObjectReader& object) {
  MultipleScattering scattering;
  const json* block = object.optional("multiple_scattering");
  if (!block) return scattering;
  if (block->is_string()) {
    object.check(*block == "off", "multiple_scattering",
                 "must be \"off\" or an object with \"octaves\", \"attenuation\" and \"contribution\"");
    scattering.octaves = 1;
    return scattering;
  }
  ObjectReader reader(object.reader(), *block, object.path_of("multiple_scattering"));
  scattering.octaves = reader.integer_or("octaves", scattering.octaves);
  reader.check(scattering.octaves >= 1 && scattering.octaves <= 8, "octaves", "must be 1 (single scattering) to 8");
  scattering.attenuation = reader.number_or("attenuation", scattering.attenuation);
  reader.check(scattering.attenuation > 0.0f && scattering.attenuation <= 1.0f, "attenuation", "must be in (0, 1]");
  scattering.contribution = reader.number_or("contribution", scattering.contribution);
  reader.check(scattering.contribution >= 0.0f && scattering.contribution <= 1.0f, "contribution",
               "must be in [0, 1]");
  reader.finish();
  return scattering;
}

// "sequence": the timing of a volume whose file names a frame pattern.
void read_sequence_settings(ObjectReader& object, VolumeEntry& entry) {
  std::optional<FramePattern> pattern;
  try {
    pattern = parse_frame_pattern(entry.file);
  } catch (const std::invalid_argument& error) {
    object.check(false, "file", error.what());
  }
  const json* value = object.optional("sequence");
  if (!value) return;
  object.check(pattern.has_value(), "sequence",
               "needs a file name with a frame number field (\"smoke.####.vdb\", \"smoke.$F4.vdb\" or \"smoke.%04d.vdb\")");
  ObjectReader sequence(object.reader(), *value, object.path_of("sequence"));
  SequenceSettings& settings = entry.sequence;
  if (const json* frames = sequence.optional("frames")) {
    const bool pair = frames->is_array() && frames->size() == 2 && (*frames)[0].is_number_integer() &&
                      (*frames)[1].is_number_integer();
    sequence.check(pair, "frames", "must be [first, last], two whole file frame numbers");
    settings.first = (*frames)[0].get<int>();
    settings.last = (*frames)[1].get<int>();
    sequence.check(*settings.first >= 0 && *settings.first <= *settings.last, "frames",
                   "must have 0 <= first <= last, got [" + std::to_string(*settings.first) + ", " +
                       std::to_string(*settings.last) + "]");
  }
  settings.fps = sequence.number_or("fps", settings.fps);
  sequence.check(settings.fps > 0.0f && settings.fps <= 1000.0f, "fps", "must be above 0 and at most 1000 frames per second");
  settings.offset = sequence.optional_integer("offset");
  settings.loop = choice<bool>(sequence, "mode", false, {{"hold", false}, {"loop", true}});
  sequence.finish();
}

VolumeEntry read_volume(ObjectReader& object, const std::filesystem::path& scene_dir) {
  VolumeEntry entry;
  entry.file = asset_path(object, scene_dir);
  entry.name = name_or(object, entry.file.stem().string());
  entry.grid = object.string("grid");
  object.check(!entry.grid.empty(), "grid", "must not be empty");
  entry.transform = transform_or_identity(object);
  entry.extinction_scale = object.number("extinction_scale");
  object.check(entry.extinction_scale >= 0.0f, "extinction_scale", "must be >= 0");
  entry.albedo = object.vec3_or("albedo", glm::vec3(1.0f));
  object.check(glm::all(glm::greaterThanEqual(entry.albedo, glm::vec3(0.0f))) &&
                   glm::all(glm::lessThanEqual(entry.albedo, glm::vec3(1.0f))),
               "albedo", "each component must be in [0, 1]");
  entry.majorant_brick_size = object.integer_or("majorant_brick_size", 8);
  object.check(entry.majorant_brick_size >= 2 && entry.majorant_brick_size <= 64, "majorant_brick_size",
               "must be 2 to 64 voxels");
  const json* cache = object.optional("lighting_cache");
  if (cache && cache->is_string()) {
    object.check(*cache == "off", "lighting_cache", "must be \"off\" or an object with \"downsample\"");
    entry.lighting_cache = false;
  } else if (cache) {
    ObjectReader cache_object(object.reader(), *cache, object.path_of("lighting_cache"));
    entry.lighting_cache_downsample = cache_object.number_or("downsample", entry.lighting_cache_downsample);
    cache_object.check(entry.lighting_cache_downsample >= 1.0f && entry.lighting_cache_downsample <= 8.0f, "downsample",
                       "must be 1 to 8 voxels per cache cell");
    cache_object.finish();
  }
  entry.multiple_scattering = read_multiple_scattering(object);
  entry.sky_light = object.number_or("sky_light", entry.sky_light);
  object.check(entry.sky_light >= 0.0f && entry.sky_light <= 4.0f, "sky_light",
               "must be 0 (no sky light) to 4 (the sky's share of the volume's light)");
  read_sequence_settings(object, entry);
  return entry;
}

std::string lowercase_extension(const std::filesystem::path& file) {
  std::string extension = file.extension().string();
  std::transform(extension.begin(), extension.end(), extension.begin(),
                 [](unsigned char c) { return char(std::tolower(c)); });
  return extension;
}

HairEntry read_hair(ObjectReader& object, const std::filesystem::path& scene_dir) {
  HairEntry entry;
  entry.file = asset_path(object, scene_dir);
  const std::string extension = lowercase_extension(entry.file);
  object.check(extension == ".tfx" || extension == ".hair" || extension == ".gltf" || extension == ".glb", "file",
               "unknown hair format '" + extension + "' (expected .tfx, .hair, .gltf or .glb)");
  entry.name = name_or(object, entry.file.stem().string());
  entry.transform = transform_or_identity(object);
  entry.width = object.optional_number("width");
  object.check(!entry.width || *entry.width > 0.0f, "width", "must be > 0");
  // Only cyHair stores absolute strand thickness; the others need a width here.
  object.check(entry.width || extension == ".hair", "width",
               "required for " + extension + " files, which store no absolute strand widths");
  entry.opacity = object.optional_number("opacity");
  object.check(!entry.opacity || (*entry.opacity >= 0.0f && *entry.opacity <= 1.0f), "opacity", "must be in [0, 1]");
  entry.color = object.optional_vec3("color");
  object.check(!entry.color || glm::all(glm::greaterThanEqual(*entry.color, glm::vec3(0.0f))), "color",
               "components must be >= 0");
  return entry;
}

ShadowSettings read_shadow(const Reader& reader, const json& value, const std::string& path) {
  ObjectReader object(reader, value, path);
  ShadowSettings shadow;
  read_shadow_overrides(object).apply(shadow);
  // The keys a sweep cannot override: how far the map reaches and the cascades' blend.
  shadow.distance = object.number_or("distance", shadow.distance);
  object.check(shadow.distance >= 0.0f, "distance", "must be >= 0 (0: the camera's far plane)");
  shadow.cascade_blend = object.number_or("cascade_blend", shadow.cascade_blend);
  object.check(shadow.cascade_blend >= 0.0f && shadow.cascade_blend <= 0.5f, "cascade_blend", "must be 0 to 0.5");
  object.finish();
  return shadow;
}

SceneShadows read_scene_shadows(const Reader& reader, const json& value) {
  ObjectReader object(reader, value, "shadows");
  SceneShadows shadows;
  shadows.budget_mib = object.number_or("budget_mib", float(shadows.budget_mib));
  object.check(shadows.budget_mib >= 0.0, "budget_mib", "must be >= 0 (0: the device's storage buffer range)");
  shadows.fit_budget = object.boolean_or("fit_budget", shadows.fit_budget);
  shadows.clusters = object.integer_or("clusters", shadows.clusters);
  object.check(shadows.clusters >= 0 && shadows.clusters <= 8, "clusters",
               "must be 0 (off) to 8 maps per light, got " + std::to_string(shadows.clusters));
  object.finish();
  return shadows;
}

VolumeShading read_volume_shading(const Reader& reader, const json& value) {
  ObjectReader object(reader, value, "volume_shading");
  VolumeShading shading;
  shading.mode = choice<VolumeShading::Mode>(object, "mode", shading.mode,
                                             {{"fast", VolumeShading::Mode::fast},
                                              {"reference", VolumeShading::Mode::reference},
                                              {"hidden", VolumeShading::Mode::hidden}});
  shading.resolution_divisor = object.integer_or("resolution_divisor", shading.resolution_divisor);
  object.check(shading.resolution_divisor == 1 || shading.resolution_divisor == 2 || shading.resolution_divisor == 4,
               "resolution_divisor", "must be 1, 2 or 4, got " + std::to_string(shading.resolution_divisor));
  shading.step_voxels = object.number_or("step_voxels", shading.step_voxels);
  object.check(shading.step_voxels >= 0.125f && shading.step_voxels <= 4.0f, "step_voxels",
               "must be 0.125 to 4 voxels");
  object.finish();
  return shading;
}

// The medium keys a fog and its boxes share, over the values `medium` starts with.
FogMedium read_fog_medium(ObjectReader& object, FogMedium medium) {
  medium.scattering = object.number_or("scattering", medium.scattering);
  object.check(medium.scattering >= 0.0f && medium.scattering <= kFogMaxCoefficient, "scattering",
               "must be 0 to 100 per metre (sigma_s)");
  medium.absorption = object.number_or("absorption", medium.absorption);
  object.check(medium.absorption >= 0.0f && medium.absorption <= kFogMaxCoefficient, "absorption",
               "must be 0 to 100 per metre (sigma_a)");
  medium.color = object.vec3_or("color", medium.color);
  object.check(glm::all(glm::greaterThanEqual(medium.color, glm::vec3(0.0f))) &&
                   glm::all(glm::lessThanEqual(medium.color, glm::vec3(1.0f))),
               "color", "each component must be in [0, 1] (the scattered light's tint)");
  medium.phase_g = object.number_or("phase_g", medium.phase_g);
  object.check(medium.phase_g >= -kFogMaxPhaseG && medium.phase_g <= kFogMaxPhaseG, "phase_g",
               "must be -0.95 to 0.95 (Henyey-Greenstein: 0 isotropic, > 0 forward)");
  return medium;
}

FogBox read_fog_box(ObjectReader& object) {
  FogBox box;
  box.bounds.min = object.vec3("min");
  box.bounds.max = object.vec3("max");
  object.check(glm::all(glm::lessThan(box.bounds.min, box.bounds.max)), "max",
               "must be greater than min on every axis");
  box.medium = read_fog_medium(object, FogMedium{});
  object.finish();
  return box;
}

// "fog": a global medium and its boxes, the sky's share and the froxel grid.
Fog read_fog(const Reader& reader, const json& value) {
  ObjectReader object(reader, value, "fog");
  Fog fog;
  fog.global = read_fog_medium(object, fog.global);
  fog.sky_light = object.number_or("sky_light", fog.sky_light);
  object.check(fog.sky_light >= 0.0f && fog.sky_light <= kFogMaxSkyLight, "sky_light",
               "must be 0 (no sky light) to 4 (the sky's share of the fog's light)");
  fog.grid.froxel_pixels = object.integer_or("froxel_pixels", fog.grid.froxel_pixels);
  object.check(fog.grid.froxel_pixels >= kFogMinFroxelPixels && fog.grid.froxel_pixels <= kFogMaxFroxelPixels,
               "froxel_pixels",
               "must be 4 to 64 pixels a side");
  fog.grid.slices = object.integer_or("slices", fog.grid.slices);
  object.check(fog.grid.slices >= kFogMinSlices && fog.grid.slices <= kFogMaxSlices, "slices",
               "must be 8 to 256 depth slices");
  fog.grid.distance = object.number_or("distance", fog.grid.distance);
  object.check(fog.grid.distance >= 0.0f, "distance", "must be >= 0 metres (0: to the scene's far side)");
  if (const json* boxes = object.optional("boxes")) {
    const std::string path = object.path_of("boxes");
    reader.expect(boxes->is_array(), path, "expected an array of boxes, got " + describe_type(*boxes));
    for (std::size_t i = 0; i < boxes->size(); ++i) {
      ObjectReader box(reader, (*boxes)[i], index_path(path, i));
      fog.boxes.push_back(read_fog_box(box));
    }
  }
  object.finish();
  return fog;
}

// "size": [width, height] of a rect light, in world units, each > 0.
glm::vec2 read_rect_size(ObjectReader& object) {
  const json& value = object.required("size");
  const std::string path = object.path_of("size");
  object.reader().expect(value.is_array() && value.size() == 2, path, "expected [width, height]");
  const glm::vec2 size(float(object.reader().number(value[0], index_path(path, 0))),
                       float(object.reader().number(value[1], index_path(path, 1))));
  object.check(size.x > 0.0f && size.y > 0.0f, "size", "width and height must be > 0");
  return size;
}

Light read_light(ObjectReader& object, std::size_t index) {
  Light light;
  light.name = name_or(object, "light" + std::to_string(index));
  light.type = choice<LightType>(
      object, "type", LightType::directional,
      {{"directional", LightType::directional}, {"spot", LightType::spot}, {"point", LightType::point},
       {"rect", LightType::rect}, {"disk", LightType::disk}, {"sphere", LightType::sphere}},
      true);
  light.color = object.vec3_or("color", glm::vec3(1.0f));
  object.check(glm::all(glm::greaterThanEqual(light.color, glm::vec3(0.0f))), "color", "components must be >= 0");
  light.intensity = object.number_or("intensity", 1.0f);
  object.check(light.intensity >= 0.0f, "intensity", "must be >= 0");

  const bool spot = light.type == LightType::spot, point = light.type == LightType::point;
  const bool rect = light.type == LightType::rect, disk = light.type == LightType::disk;
  const bool sphere = light.type == LightType::sphere, area = is_area_light(light.type);
  for (const char* key : {"inner_cone_deg", "outer_cone_deg"})
    object.check(spot || !object.has(key), key, "only spot lights have this");
  object.check(spot || rect || disk || !object.has("target"), "target", "only spot, rect and disk lights have this");
  for (const char* key : {"position", "range"})
    object.check(spot || point || area || !object.has(key), key, "only spot, point and area lights have this");
  object.check(rect || !object.has("size"), "size", "only rect lights have this");
  object.check(disk || sphere || !object.has("radius"), "radius", "only disk and sphere lights have this");
  object.check(rect || disk || !object.has("two_sided"), "two_sided", "only rect and disk lights have this");
  object.check(area || !object.has("virtual_lights"), "virtual_lights", "only area lights have this");
  object.check(!sphere || !object.has("direction"), "direction", "sphere lights shine every way; remove it");
  object.check(!point || !object.has("direction"), "direction", "point lights shine every way; remove it");
  light.range = object.number_or("range", 0.0f);
  object.check(light.range >= 0.0f, "range", "must be >= 0 (0: no limit)");
  glm::vec3 direction{0.0f, -1.0f, 0.0f};
  if (point) {
    light.position = object.vec3("position");
  } else if (area) {
    light.position = object.vec3("position");
    if (!sphere) {
      object.check(object.has("direction") != object.has("target"), "direction",
                   "give exactly one of 'direction' and 'target' (where the light faces)");
      direction = object.has("target") ? object.vec3("target") - light.position : object.vec3("direction");
      light.two_sided = object.boolean_or("two_sided", false);
    }
    if (rect) {
      light.size = read_rect_size(object);
    } else {
      light.radius = object.number("radius");
      object.check(light.radius > 0.0f, "radius", "must be > 0");
    }
    light.virtual_lights = object.integer_or("virtual_lights", light.virtual_lights);
    object.check(light.virtual_lights >= 1 && light.virtual_lights <= kMaxVirtualLights, "virtual_lights",
                 "must be 1 to " + std::to_string(kMaxVirtualLights) + " (maps for its soft shadows)");
  } else if (spot) {
    light.position = object.vec3("position");
    object.check(object.has("direction") != object.has("target"), "direction",
                 "give exactly one of 'direction' and 'target'");
    direction = object.has("target") ? object.vec3("target") - light.position : object.vec3("direction");
    light.outer_cone_angle = glm::radians(object.number("outer_cone_deg"));
    light.inner_cone_angle = glm::radians(object.number("inner_cone_deg"));
    object.check(light.outer_cone_angle > 0.0f && light.outer_cone_angle < glm::radians(90.0f), "outer_cone_deg",
                 "must be between 0 and 90 degrees (half-angle from the axis)");
    object.check(light.inner_cone_angle >= 0.0f && light.inner_cone_angle <= light.outer_cone_angle,
                 "inner_cone_deg", "must be between 0 and outer_cone_deg");
  } else {
    direction = object.vec3("direction");
  }
  object.check(point || sphere || glm::length(direction) > 1e-6f, object.has("target") ? "target" : "direction",
               "gives no direction (zero length)");
  light.direction = glm::normalize(direction);
  if (const json* shadow = object.optional("shadow")) light.shadow = read_shadow(object.reader(), *shadow, object.path_of("shadow"));
  return light;
}

Camera read_camera(ObjectReader& object, std::size_t index) {
  Camera camera;
  camera.name = name_or(object, "camera" + std::to_string(index));
  camera.position = object.vec3("position");
  camera.target = object.vec3("target");
  camera.up = object.vec3_or("up", camera.up);
  const float fov_deg = object.number("vertical_fov_deg");
  object.check(fov_deg > 0.0f && fov_deg < 180.0f, "vertical_fov_deg", "must be between 0 and 180");
  camera.vertical_fov = glm::radians(fov_deg);
  camera.near_plane = object.number("near");
  camera.far_plane = object.number("far");
  object.check(camera.near_plane > 0.0f, "near", "must be > 0");
  object.check(camera.far_plane > camera.near_plane, "far", "must be greater than near");
  const glm::vec3 view = camera.target - camera.position;
  object.check(glm::length(view) > 1e-6f, "target", "is the same point as position");
  object.check(glm::length(glm::cross(glm::normalize(view), camera.up)) > 1e-4f, "up",
               "is zero or parallel to the viewing direction");
  camera.up = glm::normalize(camera.up);
  return camera;
}

// Reads the array `key` of objects with `read_entry`; names must be unique.
template <class Entry, class ReadEntry>
std::vector<Entry> read_list(ObjectReader& top, const std::string& key, ReadEntry read_entry) {
  std::vector<Entry> entries;
  const json* list = top.optional(key);
  if (list == nullptr) return entries;
  top.reader().expect(list->is_array(), key, "expected an array, got " + describe_type(*list));
  for (std::size_t i = 0; i < list->size(); ++i) {
    ObjectReader object(top.reader(), (*list)[i], index_path(key, i));
    Entry entry = read_entry(object, i);
    object.finish();
    for (std::size_t j = 0; j < entries.size(); ++j)
      object.check(entries[j].name != entry.name, "name",
                   "'" + entry.name + "' is already used by " + index_path(key, j) + "; names must be unique");
    entries.push_back(std::move(entry));
  }
  return entries;
}

}  // namespace

ShadowOverrides read_shadow_overrides(ObjectReader& object, bool with_light_keys) {
  ShadowOverrides shadow;
  // A name; which names exist is the renderer's registry's to say (passes/shadows/techniques/).
  shadow.technique = object.optional("technique") ? std::optional(object.string("technique")) : std::nullopt;
  object.check(!shadow.technique || !shadow.technique->empty(), "technique", "must name a shadow technique");
  auto whole_number = [&](const char* key, bool (*allowed)(int), const std::string& range) {
    const std::optional<int> value = object.optional_integer(key);
    object.check(!value || allowed(*value), key, "must be " + range + ", got " + std::to_string(value.value_or(0)));
    return value;
  };
  shadow.nodes = whole_number("nodes", [](int n) { return n == 4 || n == 8 || n == 12 || n == 16; }, "4, 8, 12 or 16");
  shadow.resolution = whole_number("resolution", [](int r) { return r >= 16 && r <= 16384; }, "16 to 16384 texels");
  shadow.filter = optional_choice<ShadowFilter>(
      object, "filter", {{"point", ShadowFilter::point}, {"bilinear", ShadowFilter::bilinear}, {"trilinear", ShadowFilter::trilinear}});
  shadow.kernel = optional_choice<ShadowKernel>(
      object, "kernel", {{"none", ShadowKernel::none}, {"box", ShadowKernel::box}, {"gaussian", ShadowKernel::gaussian}});
  shadow.kernel_radius = whole_number("kernel_radius", [](int r) { return r >= 1 && r <= 4; }, "1 to 4 texels");
  shadow.sort = object.optional_boolean("sort");
  shadow.build = optional_choice<ShadowBuild>(object, "build", {{"lists", ShadowBuild::lists}, {"fixed", ShadowBuild::fixed}});
  shadow.fit = optional_choice<ShadowFit>(object, "fit", {{"view", ShadowFit::view}, {"scene", ShadowFit::scene}});
  shadow.cascades = whole_number("cascades", [](int n) { return n >= 1 && n <= 4; }, "1 to 4");
  shadow.clusters = whole_number("clusters", [](int n) { return n >= 0 && n <= 8; }, "0 (off) to 8 maps");
  shadow.layout = optional_choice<ShadowLayout>(object, "layout", {{"dense", ShadowLayout::dense}, {"paged", ShadowLayout::paged}});
  shadow.virtual_resolution = whole_number(
      "virtual_resolution", [](int r) { return r >= 256 && r <= 262144 && (r & (r - 1)) == 0; },
      "a power of two, 256 to 16384 texels (to 262144 for directional lights)");
  shadow.page_size = whole_number("page_size", [](int p) { return p == 32 || p == 64 || p == 128; }, "32, 64 or 128 texels");
  if (object.optional("page_pool_mib")) {
    shadow.page_pool_mib = object.number("page_pool_mib");
    object.check(*shadow.page_pool_mib > 0.0 && *shadow.page_pool_mib <= 4096.0, "page_pool_mib",
                 "must be more than 0 and at most 4096 MiB");
  }
  if (object.optional("page_lod_bias")) {
    shadow.page_lod_bias = float(object.number("page_lod_bias"));
    object.check(*shadow.page_lod_bias >= -4.0f && *shadow.page_lod_bias <= 8.0f, "page_lod_bias", "must be -4 to 8 levels");
  }
  if (object.optional("page_volume_lod_bias")) {
    shadow.page_volume_lod_bias = float(object.number("page_volume_lod_bias"));
    object.check(*shadow.page_volume_lod_bias >= 0.0f && *shadow.page_volume_lod_bias <= 8.0f, "page_volume_lod_bias",
                 "must be 0 to 8 levels");
  }
  shadow.page_builds_per_frame =
      whole_number("page_builds_per_frame", [](int n) { return n >= 0 && n <= 65536; }, "0 (no limit) to 65536 pages");
  if (with_light_keys)
    shadow.virtual_lights = whole_number("virtual_lights", [](int n) { return n >= 1 && n <= kMaxVirtualLights; },
                                         "1 to " + std::to_string(kMaxVirtualLights) + " (area lights' maps)");
  if (const json* parameters = object.optional("parameters")) {
    const std::string parameters_path = object.path_of("parameters");
    object.reader().expect(parameters->is_object(), parameters_path,
                           "expected an object of numbers, got " + describe_type(*parameters));
    for (const auto& [key, number] : parameters->items())
      shadow.parameters[key] = object.reader().number(number, child_path(parameters_path, key));
  }
  return shadow;
}

SceneDescription parse_scene_description(std::string_view json_text, const std::filesystem::path& file) {
  const Reader reader(file);
  const json document = parse_json(reader, json_text);
  ObjectReader top(reader, document, "");
  const json& version = top.required("version");
  reader.expect(reader.integer(version, "version") == kSceneFormatVersion, "version",
                "unsupported version " + version.dump() + " (this build reads version " +
                    std::to_string(kSceneFormatVersion) + ")");

  SceneDescription scene;
  scene.file = file;
  const std::filesystem::path scene_dir = file.parent_path();
  scene.description = top.string_or("description", "");
  scene.models = read_list<ModelEntry>(top, "models", [&](ObjectReader& o, std::size_t) { return read_model(o, scene_dir); });
  scene.volumes = read_list<VolumeEntry>(top, "volumes", [&](ObjectReader& o, std::size_t) { return read_volume(o, scene_dir); });
  scene.hair = read_list<HairEntry>(top, "hair", [&](ObjectReader& o, std::size_t) { return read_hair(o, scene_dir); });
  scene.lights = read_list<Light>(top, "lights", [&](ObjectReader& o, std::size_t i) {
    Light light = read_light(o, i);
    scene.light_animations.push_back(detail::read_light_animation(o, light));
    return light;
  });
  scene.cameras = read_list<Camera>(top, "cameras", [&](ObjectReader& o, std::size_t i) {
    Camera camera = read_camera(o, i);
    scene.camera_animations.push_back(detail::read_camera_animation(o));
    return camera;
  });
  if (const json* shading = top.optional("volume_shading")) scene.volume_shading = read_volume_shading(reader, *shading);
  if (const json* shadows = top.optional("shadows")) scene.shadows = read_scene_shadows(reader, *shadows);
  if (const json* fog = top.optional("fog")) scene.fog = read_fog(reader, *fog);
  // A scene of models may take its cameras from their glTF files (load_scene checks it has one).
  reader.expect(!scene.cameras.empty() || !scene.models.empty(), "cameras", "a scene needs at least one camera");
  top.finish();
  return scene;
}

SceneDescription read_scene_description(const std::filesystem::path& file) {
  const std::vector<std::byte> bytes = detail::read_file_bytes(file, kMaxSceneFileBytes);
  return parse_scene_description(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), file);
}

}  // namespace avsm::scene
