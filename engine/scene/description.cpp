// Strict reading of scene files. Every value goes through a reader that knows
// its JSON path, so every message can say exactly where the problem is.
#include "scene/description.h"

#include "scene/binary_reader.h"
#include "scene/load_error.h"

#include <nlohmann/json.hpp>

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cctype>
#include <cmath>
#include <set>

namespace avsm::scene {
namespace {

using json = nlohmann::json;

constexpr std::uint64_t kMaxSceneFileBytes = 64ull << 20;

std::string child_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}
std::string index_path(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

std::string describe_type(const json& value) {
  switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "true/false";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    case json::value_t::number_float: return "a number with a fraction";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "an integer";
    default: return "something else";
  }
}

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// Knows the file; every failure names it and the JSON path.
class Reader {
 public:
  explicit Reader(std::filesystem::path file) : file_(std::move(file)) {}
  const std::filesystem::path& file() const { return file_; }

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const {
    throw LoadError(file_, (path.empty() ? std::string("top level") : path) + ": " + problem);
  }
  void expect(bool condition, const std::string& path, const std::string& problem) const {
    if (!condition) fail(path, problem);
  }

  std::string string(const json& value, const std::string& path) const {
    expect(value.is_string(), path, "expected a string, got " + describe_type(value));
    return value.get<std::string>();
  }
  bool boolean(const json& value, const std::string& path) const {
    expect(value.is_boolean(), path, "expected true or false, got " + describe_type(value));
    return value.get<bool>();
  }
  double number(const json& value, const std::string& path) const {
    expect(value.is_number(), path, "expected a number, got " + describe_type(value));
    const double result = value.get<double>();
    expect(std::isfinite(result), path, "expected a finite number");
    return result;
  }
  int integer(const json& value, const std::string& path) const {
    expect(value.is_number_integer(), path, "expected a whole number, got " + describe_type(value));
    constexpr std::int64_t kLimit = 1 << 30;
    const bool in_range = value.is_number_unsigned() ? value.get<std::uint64_t>() <= std::uint64_t(kLimit)
                                                     : std::abs(value.get<std::int64_t>()) <= kLimit;
    expect(in_range, path, "number is out of range");
    return static_cast<int>(value.get<std::int64_t>());
  }
  glm::vec3 vec3(const json& value, const std::string& path) const {
    expect(value.is_array() && value.size() == 3, path, "expected an array of 3 numbers, got " + describe_type(value) +
                                                            (value.is_array() ? " of " + std::to_string(value.size()) : ""));
    return glm::vec3(float(number(value[0], index_path(path, 0))), float(number(value[1], index_path(path, 1))),
                     float(number(value[2], index_path(path, 2))));
  }

 private:
  std::filesystem::path file_;
};

// One JSON object: hands out its members and, at finish(), rejects any member
// nobody asked for (with the closest known key as a hint).
class ObjectReader {
 public:
  ObjectReader(const Reader& reader, const json& value, std::string path)
      : reader_(reader), value_(value), path_(std::move(path)) {
    reader_.expect(value.is_object(), path_, "expected an object, got " + describe_type(value));
  }

  const std::string& path() const { return path_; }
  std::string path_of(const std::string& key) const { return child_path(path_, key); }
  const Reader& reader() const { return reader_; }

  const json* optional(const std::string& key) {
    known_.push_back(key);
    const auto found = value_.find(key);
    return found == value_.end() ? nullptr : &*found;
  }
  const json& required(const std::string& key) {
    const json* value = optional(key);
    if (value == nullptr) reader_.fail(path_of(key), "required key is missing");
    return *value;
  }
  bool has(const std::string& key) const { return value_.contains(key); }

  void finish() const {
    for (const auto& [key, unused] : value_.items()) {
      if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
      std::string hint;
      std::size_t best = 3;  // suggest only near misses
      for (const std::string& candidate : known_)
        if (const std::size_t d = edit_distance(key, candidate); d < best) best = d, hint = candidate;
      std::string known_list;
      for (const std::string& candidate : known_) known_list += (known_list.empty() ? "" : ", ") + candidate;
      reader_.fail(path_of(key), "unknown key" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)") +
                                     "; allowed here: " + known_list);
    }
  }

  // Typed accessors.
  std::string string(const std::string& key) { return reader_.string(required(key), path_of(key)); }
  std::string string_or(const std::string& key, const std::string& fallback) {
    const json* value = optional(key);
    return value ? reader_.string(*value, path_of(key)) : fallback;
  }
  float number(const std::string& key) { return float(reader_.number(required(key), path_of(key))); }
  float number_or(const std::string& key, float fallback) {
    const json* value = optional(key);
    return value ? float(reader_.number(*value, path_of(key))) : fallback;
  }
  std::optional<float> optional_number(const std::string& key) {
    const json* value = optional(key);
    return value ? std::optional<float>(float(reader_.number(*value, path_of(key)))) : std::nullopt;
  }
  int integer_or(const std::string& key, int fallback) {
    const json* value = optional(key);
    return value ? reader_.integer(*value, path_of(key)) : fallback;
  }
  bool boolean_or(const std::string& key, bool fallback) {
    const json* value = optional(key);
    return value ? reader_.boolean(*value, path_of(key)) : fallback;
  }
  glm::vec3 vec3(const std::string& key) { return reader_.vec3(required(key), path_of(key)); }
  glm::vec3 vec3_or(const std::string& key, const glm::vec3& fallback) {
    const json* value = optional(key);
    return value ? reader_.vec3(*value, path_of(key)) : fallback;
  }
  std::optional<glm::vec3> optional_vec3(const std::string& key) {
    const json* value = optional(key);
    return value ? std::optional<glm::vec3>(reader_.vec3(*value, path_of(key))) : std::nullopt;
  }

  void check(bool condition, const std::string& key, const std::string& problem) const {
    reader_.expect(condition, path_of(key), problem);
  }

 private:
  const Reader& reader_;
  const json& value_;
  std::string path_;
  std::vector<std::string> known_;
};

// ---- pieces ----

template <class Enum>
Enum choice(ObjectReader& object, const std::string& key, Enum fallback,
            const std::vector<std::pair<std::string, Enum>>& options, bool is_required = false) {
  const json* value = is_required ? &object.required(key) : object.optional(key);
  if (value == nullptr) return fallback;
  const std::string text = object.reader().string(*value, object.path_of(key));
  std::string allowed;
  for (const auto& [name, option] : options) {
    if (name == text) return option;
    allowed += (allowed.empty() ? "" : ", ") + name;
  }
  object.reader().fail(object.path_of(key), "'" + text + "' is not one of " + allowed);
}

glm::mat4 rotation_from_degrees(const glm::vec3& degrees) {
  const glm::vec3 r = glm::radians(degrees);
  const glm::mat4 identity(1.0f);
  return glm::rotate(identity, r.z, glm::vec3(0, 0, 1)) * glm::rotate(identity, r.y, glm::vec3(0, 1, 0)) *
         glm::rotate(identity, r.x, glm::vec3(1, 0, 0));
}

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
    result = glm::translate(glm::mat4(1.0f), translation) * rotation_from_degrees(rotation) *
             glm::scale(glm::mat4(1.0f), scale);
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

ModelEntry read_model(ObjectReader& object, const std::filesystem::path& scene_dir) {
  ModelEntry entry;
  entry.file = asset_path(object, scene_dir);
  entry.name = name_or(object, entry.file.stem().string());
  entry.transform = transform_or_identity(object);
  entry.missing_normals = choice<NormalGeneration>(object, "missing_normals", NormalGeneration::flat,
                                                   {{"flat", NormalGeneration::flat}, {"smooth", NormalGeneration::smooth}});
  return entry;
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
  // A name; which names exist is the renderer's registry's to say (passes/techniques/).
  shadow.technique = object.string_or("technique", shadow.technique);
  object.check(!shadow.technique.empty(), "technique", "must name a shadow technique");
  shadow.nodes = object.integer_or("nodes", shadow.nodes);
  object.check(shadow.nodes == 4 || shadow.nodes == 8 || shadow.nodes == 12 || shadow.nodes == 16, "nodes",
               "must be 4, 8, 12 or 16, got " + std::to_string(shadow.nodes));
  shadow.resolution = object.integer_or("resolution", shadow.resolution);
  object.check(shadow.resolution >= 16 && shadow.resolution <= 16384, "resolution",
               "must be 16 to 16384 texels, got " + std::to_string(shadow.resolution));
  shadow.filter = choice<ShadowFilter>(object, "filter", shadow.filter,
                                       {{"point", ShadowFilter::point},
                                        {"bilinear", ShadowFilter::bilinear},
                                        {"trilinear", ShadowFilter::trilinear}});
  shadow.kernel = choice<ShadowKernel>(object, "kernel", shadow.kernel,
                                       {{"none", ShadowKernel::none},
                                        {"box", ShadowKernel::box},
                                        {"gaussian", ShadowKernel::gaussian}});
  shadow.kernel_radius = object.integer_or("kernel_radius", shadow.kernel_radius);
  object.check(shadow.kernel_radius >= 1 && shadow.kernel_radius <= 4, "kernel_radius",
               "must be 1 to 4 texels, got " + std::to_string(shadow.kernel_radius));
  shadow.sort = object.boolean_or("sort", shadow.sort);
  shadow.build = choice<ShadowBuild>(object, "build", shadow.build,
                                     {{"lists", ShadowBuild::lists}, {"fixed", ShadowBuild::fixed}});
  shadow.fit = choice<ShadowFit>(object, "fit", shadow.fit, {{"view", ShadowFit::view}, {"scene", ShadowFit::scene}});
  shadow.distance = object.number_or("distance", shadow.distance);
  object.check(shadow.distance >= 0.0f, "distance", "must be >= 0 (0: the camera's far plane)");
  shadow.cascades = object.integer_or("cascades", shadow.cascades);
  object.check(shadow.cascades >= 1 && shadow.cascades <= 4, "cascades",
               "must be 1 to 4, got " + std::to_string(shadow.cascades));
  shadow.cascade_blend = object.number_or("cascade_blend", shadow.cascade_blend);
  object.check(shadow.cascade_blend >= 0.0f && shadow.cascade_blend <= 0.5f, "cascade_blend", "must be 0 to 0.5");
  shadow.clusters = object.integer_or("clusters", shadow.clusters);
  object.check(shadow.clusters >= 0 && shadow.clusters <= 8, "clusters",
               "must be 0 (off) to 8 maps, got " + std::to_string(shadow.clusters));
  if (const json* parameters = object.optional("parameters")) {
    const std::string parameters_path = object.path_of("parameters");
    reader.expect(parameters->is_object(), parameters_path, "expected an object of numbers, got " + describe_type(*parameters));
    for (const auto& [key, number] : parameters->items())
      shadow.parameters[key] = reader.number(number, child_path(parameters_path, key));
  }
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

Light read_light(ObjectReader& object, std::size_t index) {
  Light light;
  light.name = name_or(object, "light" + std::to_string(index));
  light.type = choice<LightType>(
      object, "type", LightType::directional,
      {{"directional", LightType::directional}, {"spot", LightType::spot}, {"point", LightType::point}}, true);
  light.color = object.vec3_or("color", glm::vec3(1.0f));
  object.check(glm::all(glm::greaterThanEqual(light.color, glm::vec3(0.0f))), "color", "components must be >= 0");
  light.intensity = object.number_or("intensity", 1.0f);
  object.check(light.intensity >= 0.0f, "intensity", "must be >= 0");

  const bool spot = light.type == LightType::spot, point = light.type == LightType::point;
  for (const char* key : {"target", "inner_cone_deg", "outer_cone_deg"})
    object.check(spot || !object.has(key), key, "only spot lights have this");
  for (const char* key : {"position", "range"})
    object.check(spot || point || !object.has(key), key, "only spot and point lights have this");
  object.check(!point || !object.has("direction"), "direction", "point lights shine every way; remove it");
  light.range = object.number_or("range", 0.0f);
  object.check(light.range >= 0.0f, "range", "must be >= 0 (0: no limit)");
  glm::vec3 direction{0.0f, -1.0f, 0.0f};
  if (point) {
    light.position = object.vec3("position");
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
  object.check(point || glm::length(direction) > 1e-6f, object.has("target") ? "target" : "direction",
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

// nlohmann::json keeps the last of repeated keys; a scene file with two
// "nodes" is a mistake, so the parse callback tracks the JSON path and refuses them.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const Reader& reader) : reader_(reader) {}

  bool operator()(int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: frames_.push_back({}); break;
      case json::parse_event_t::array_start: frames_.push_back({true}); break;
      case json::parse_event_t::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.get<std::string>();
        if (!frame.keys.insert(frame.key).second) reader_.fail(path(), "duplicate key");
        break;
      }
      case json::parse_event_t::value: element_done(); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        element_done();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array = false;
    std::size_t index = 0;
    std::string key;
    std::set<std::string> keys;
  };
  void element_done() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
  }
  std::string path() const {
    std::string result;
    for (const Frame& frame : frames_) result = frame.is_array ? index_path(result, frame.index) : child_path(result, frame.key);
    return result;
  }

  const Reader& reader_;
  std::vector<Frame> frames_;
};

json parse_json(const Reader& reader, std::string_view text) {
  try {
    DuplicateKeyCheck check(reader);
    return json::parse(text.begin(), text.end(), std::ref(check));
  } catch (const json::exception& error) {  // parse_error, and out_of_range for numbers like 1e999
    std::string message = error.what();
    if (const auto bracket = message.find("] "); message.rfind("[json.exception", 0) == 0 && bracket != std::string::npos)
      message.erase(0, bracket + 2);
    throw LoadError(reader.file(), "invalid JSON: " + message);
  }
}

}  // namespace

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
  scene.lights = read_list<Light>(top, "lights", read_light);
  scene.cameras = read_list<Camera>(top, "cameras", read_camera);
  if (const json* shading = top.optional("volume_shading")) scene.volume_shading = read_volume_shading(reader, *shading);
  if (const json* shadows = top.optional("shadows")) scene.shadows = read_scene_shadows(reader, *shadows);
  reader.expect(top.has("cameras"), "cameras", "required key is missing (a scene needs at least one camera)");
  reader.expect(!scene.cameras.empty(), "cameras", "a scene needs at least one camera");
  top.finish();
  return scene;
}

SceneDescription read_scene_description(const std::filesystem::path& file) {
  const std::vector<std::byte> bytes = detail::read_file_bytes(file, kMaxSceneFileBytes);
  return parse_scene_description(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), file);
}

}  // namespace avsm::scene
