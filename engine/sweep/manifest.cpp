#include "sweep/manifest.h"

#include <algorithm>
#include <cstdio>
#include <map>
#include <optional>

#include "capture/capture_args.h"
#include "passes/shadows/techniques/techniques.h"
#include "scene/binary_reader.h"
#include "scene/description.h"
#include "scene/json_reader.h"

namespace avsm::sweep {
namespace fs = std::filesystem;
using nlohmann::json;
using scene::ObjectReader;
using scene::Reader;

namespace {

constexpr std::uint64_t kMaxManifestBytes = 16ull << 20;
constexpr int kMaxImageSide = 16384;
constexpr int kMaxFrames = 1000;
const std::vector<std::pair<std::string, std::string>> kCompareToChoices = {{"uncompressed", "uncompressed"}, {"none", ""}};

// The settings one manifest object sets (the defaults, an entry of a cross-product
// axis, an explicit job); the unset ones keep what they are.
struct SettingsPart {
  std::optional<std::string> scene, camera, compare_to;
  std::optional<int> width, height, frames;
  std::optional<capture::FrameRange> frame_range;  // "frame_range": "A:B" (its fps from "fps")
  std::optional<float> fps;
  std::optional<int> chunk;  // frames per job of a shot
  scene::ShadowOverrides shadow;

  void apply(JobSettings& settings) const {
    if (scene) settings.scene = *scene;
    if (camera) settings.camera = *camera;
    if (compare_to) settings.compare_to = *compare_to;
    if (width) settings.width = uint32_t(*width);
    if (height) settings.height = uint32_t(*height);
    if (frames) settings.frames = uint32_t(*frames);
    if (frame_range) {
      settings.first_frame = frame_range->first;
      settings.last_frame = frame_range->last;
    }
    if (fps) settings.fps = *fps;
    apply_overrides(shadow, settings.shadow);
  }

  // `top`'s overrides replace `base`'s; parameters merge.
  static void apply_overrides(const scene::ShadowOverrides& top, scene::ShadowOverrides& base) {
    auto take = [](const auto& from, auto& to) {
      if (from) to = from;
    };
    take(top.technique, base.technique);
    take(top.nodes, base.nodes);
    take(top.resolution, base.resolution);
    take(top.filter, base.filter);
    take(top.kernel, base.kernel);
    take(top.kernel_radius, base.kernel_radius);
    take(top.sort, base.sort);
    take(top.build, base.build);
    take(top.fit, base.fit);
    take(top.cascades, base.cascades);
    take(top.clusters, base.clusters);
    take(top.layout, base.layout);
    take(top.virtual_resolution, base.virtual_resolution);
    take(top.page_size, base.page_size);
    take(top.page_pool_mib, base.page_pool_mib);
    take(top.page_lod_bias, base.page_lod_bias);
    take(top.page_volume_lod_bias, base.page_volume_lod_bias);
    take(top.page_builds_per_frame, base.page_builds_per_frame);
    take(top.virtual_lights, base.virtual_lights);
    for (const auto& [name, value] : top.parameters) base.parameters[name] = value;
  }
};

// Which keys an object of the manifest may hold.
enum Fields : unsigned {
  kSceneFields = 1,       // scene, camera
  kResolutionFields = 2,  // width, height
  kFrames = 4,
  kShadowObject = 8,      // "shadow": {technique, nodes, ...}
  kShadowInline = 16,     // technique, nodes, ... in the object itself (a "shadows" axis entry)
  kCompareTo = 32,
  kJobFields = kSceneFields | kResolutionFields | kFrames | kShadowObject | kCompareTo,
};

class ManifestReader {
 public:
  explicit ManifestReader(const fs::path& file) : reader_(file), dir_(fs::absolute(file).parent_path()) {}

  SweepIndex read(std::string_view text) {
    const json document = scene::parse_json(reader_, text);
    ObjectReader top(reader_, document, "");
    const json& version = top.required("version");
    reader_.expect(reader_.integer(version, "version") == kManifestFormatVersion, "version",
                   "unsupported version " + version.dump() + " (this build reads version " +
                       std::to_string(kManifestFormatVersion) + ")");
    top.string_or("description", "");
    if (const json* defaults = top.optional("defaults")) {
      ObjectReader object(reader_, *defaults, "defaults");
      const SettingsPart part = read_part(object, kJobFields);
      part.apply(defaults_);
      defaults_chunk_ = part.chunk;
      object.finish();
    }
    if (const json* cross = top.optional("cross")) read_cross(*cross);
    if (const json* jobs = top.optional("jobs")) read_jobs(*jobs);
    top.finish();
    reader_.expect(!jobs_.empty(), "", "the manifest lists no jobs: give \"cross\" or \"jobs\"");
    check_references();

    SweepIndex index;
    index.manifest = fs::absolute(reader_.file()).lexically_normal().string();
    for (Job& job : jobs_) index.jobs.push_back(finish_job(job));
    return index;
  }

 private:
  struct Job {
    std::string path;  // where the manifest defines it: "jobs[2]", or "cross" for the product
    JobRecord record;
  };
  struct Axis {
    std::string name, path;
    std::vector<std::pair<std::string, SettingsPart>> entries;  // id part, settings
  };

  // The job settings the avsm-capture defaults give, before the manifest's "defaults".
  static JobSettings capture_defaults() {
    const capture::CaptureOptions defaults;
    JobSettings settings;
    settings.width = defaults.width;
    settings.height = defaults.height;
    settings.frames = defaults.frames;
    return settings;
  }

  std::string read_id(ObjectReader& object) {
    const std::string id = object.string("id");
    object.check(is_valid_job_id(id), "id",
                 "'" + id + "' is not a usable id: letters, digits, '.', '_' and '-' only (it names the job's folder), "
                 "and not slurm, manifest.json, index.json or report.html (the sweep folder's own)");
    return id;
  }

  std::optional<int> read_in_range(ObjectReader& object, const std::string& key, int lo, int hi) {
    const std::optional<int> value = object.optional_integer(key);
    object.check(!value || (*value >= lo && *value <= hi), key,
                 "must be " + std::to_string(lo) + " to " + std::to_string(hi) + ", got " + std::to_string(value.value_or(0)));
    return value;
  }

  std::string read_scene_path(ObjectReader& object) {
    const std::string text = object.string("scene");
    object.check(!text.empty(), "scene", "must not be empty (leave it out for the default scene)");
    fs::path path(text);
    if (path.is_relative()) path = dir_ / path;
    path = path.lexically_normal();
    std::error_code ec;
    object.check(fs::is_regular_file(path, ec), "scene", "no such file '" + path.string() + "' (relative paths start at the manifest's folder)");
    return path.string();
  }

  scene::ShadowOverrides read_shadow(ObjectReader& object) {
    scene::ShadowOverrides shadow = scene::read_shadow_overrides(object, /*with_light_keys=*/true);
    if (shadow.technique)
      object.check(passes::find_shadow_technique(*shadow.technique) != nullptr, "technique",
                   "'" + *shadow.technique + "' is not one of " + passes::shadow_technique_names());
    return shadow;
  }

  SettingsPart read_part(ObjectReader& object, unsigned fields) {
    SettingsPart part;
    if (fields & kSceneFields) {
      if (object.optional("scene")) part.scene = read_scene_path(object);
      if (const json* camera = object.optional("camera")) part.camera = reader_.string(*camera, object.path_of("camera"));
    }
    if (fields & kResolutionFields) {
      part.width = read_in_range(object, "width", 1, kMaxImageSide);
      part.height = read_in_range(object, "height", 1, kMaxImageSide);
    }
    if (fields & kFrames) {
      part.frames = read_in_range(object, "frames", 1, kMaxFrames);
      if (const json* range = object.optional("frame_range")) {
        capture::FrameRange parsed;
        const std::string text = reader_.string(*range, object.path_of("frame_range"));
        object.check(capture::parse_frame_range(text, parsed), "frame_range", "expected \"A:B\" with 0 <= A <= B, got '" + text + "'");
        part.frame_range = parsed;
      }
      part.fps = object.optional_number("fps");
      object.check(!part.fps || (*part.fps > 0.0f && *part.fps <= 1000.0f), "fps", "must be a frame rate in (0, 1000]");
      part.chunk = read_in_range(object, "chunk", 1, kMaxFrames);
    }
    if (fields & kShadowInline) part.shadow = read_shadow(object);
    if (fields & kShadowObject) {
      if (const json* shadow = object.optional("shadow")) {
        ObjectReader shadow_object(reader_, *shadow, object.path_of("shadow"));
        part.shadow = read_shadow(shadow_object);
        shadow_object.finish();
      }
    }
    if (fields & kCompareTo) part.compare_to = scene::optional_choice(object, "compare_to", kCompareToChoices);
    return part;
  }

  Axis read_axis(ObjectReader& cross, const std::string& name, unsigned fields) {
    Axis axis{name, cross.path_of(name), {}};
    const json* list = cross.optional(name);
    if (list == nullptr) return axis;
    reader_.expect(list->is_array() && !list->empty(), axis.path,
                   "expected a non-empty array of objects with an \"id\", got " + scene::describe_type(*list));
    for (std::size_t i = 0; i < list->size(); ++i) {
      ObjectReader object(reader_, (*list)[i], scene::index_path(axis.path, i));
      const std::string id = read_id(object);
      for (std::size_t j = 0; j < axis.entries.size(); ++j)
        object.check(axis.entries[j].first != id, "id",
                     "'" + id + "' is already the id of " + scene::index_path(axis.path, j));
      axis.entries.emplace_back(id, read_part(object, fields));
      object.finish();
    }
    return axis;
  }

  void read_cross(const json& value) {
    ObjectReader cross(reader_, value, "cross");
    // The id of a job of the product joins its entries' ids in this order.
    std::vector<Axis> axes;
    for (const auto& [name, fields] : {std::pair<const char*, unsigned>{"scenes", kSceneFields},
                                       {"resolutions", kResolutionFields}, {"shadows", kShadowInline}}) {
      Axis axis = read_axis(cross, name, fields);
      if (!axis.entries.empty()) axes.push_back(std::move(axis));
    }
    reader_.expect(!axes.empty(), "cross", "needs at least one of the axes scenes, resolutions, shadows");
    const std::vector<std::optional<std::size_t>> reference = read_cross_reference(cross, axes);
    cross.finish();

    std::vector<std::size_t> pick(axes.size(), 0);  // one entry per axis; counts like an odometer
    std::vector<Job> product;
    for (;;) {
      product.push_back({"cross", {}});
      JobRecord& job = product.back().record;
      job.id = product_id(axes, pick);
      job.settings = defaults_;
      for (std::size_t a = 0; a < axes.size(); ++a) axes[a].entries[pick[a]].second.apply(job.settings);
      std::vector<std::size_t> reference_pick = pick;
      for (std::size_t a = 0; a < axes.size(); ++a)
        if (reference[a]) reference_pick[a] = *reference[a];
      if (reference_pick != pick) job.settings.reference_job = product_id(axes, reference_pick);
      std::size_t a = axes.size();
      while (a > 0 && ++pick[a - 1] == axes[a - 1].entries.size()) pick[--a] = 0;
      if (a == 0) break;
    }
    for (Job& job : product) add_shot_chunks(job, defaults_chunk_);  // a shot in "defaults" splits each
  }

  static std::string product_id(const std::vector<Axis>& axes, const std::vector<std::size_t>& pick) {
    std::string id;
    for (std::size_t a = 0; a < axes.size(); ++a) id += (a ? "-" : "") + axes[a].entries[pick[a]].first;
    return id;
  }

  // "reference": {"shadows": "exact"}: each job is compared against the job that differs
  // from it only in taking those entries. Per axis: the entry's index, or none.
  std::vector<std::optional<std::size_t>> read_cross_reference(ObjectReader& cross, const std::vector<Axis>& axes) {
    std::vector<std::optional<std::size_t>> reference(axes.size());
    const json* value = cross.optional("reference");
    if (value == nullptr) return reference;
    ObjectReader object(reader_, *value, cross.path_of("reference"));
    for (std::size_t a = 0; a < axes.size(); ++a) {
      const json* id = object.optional(axes[a].name);
      if (id == nullptr) continue;
      const std::string text = reader_.string(*id, object.path_of(axes[a].name));
      std::string ids;
      for (std::size_t e = 0; e < axes[a].entries.size(); ++e) {
        if (axes[a].entries[e].first == text) reference[a] = e;
        ids += (e ? ", " : "") + axes[a].entries[e].first;
      }
      object.check(reference[a].has_value(), axes[a].name, "'" + text + "' is not an id of " + axes[a].path + " (" + ids + ")");
    }
    object.finish();
    return reference;
  }

  void read_jobs(const json& list) {
    reader_.expect(list.is_array(), "jobs", "expected an array, got " + scene::describe_type(list));
    for (std::size_t i = 0; i < list.size(); ++i) {
      Job job{scene::index_path("jobs", i), {}};
      ObjectReader object(reader_, list[i], job.path);
      job.record.id = read_id(object);
      job.record.settings = defaults_;
      const SettingsPart part = read_part(object, kJobFields);
      part.apply(job.record.settings);
      job.record.settings.reference_job = object.string_or("reference_job", "");
      const std::optional<int> chunk = part.chunk ? part.chunk : defaults_chunk_;
      object.check(!chunk || job.record.settings.is_shot(), "chunk", "splits a shot: give the job a \"frame_range\"");
      object.check(!job.record.settings.is_shot() || job.record.settings.reference_job.empty(), "reference_job",
                   "a shot is not compared with another job (compare its frames with avsm-compare)");
      object.finish();
      add_shot_chunks(job, chunk);
    }
  }

  // A job of one instant as it is; a shot as one job per `chunk` frames (all of them
  // without a chunk), ids "<id>.f<first>-<last>", each the shot's part of one array task.
  void add_shot_chunks(Job& job, std::optional<int> chunk) {
    JobSettings& settings = job.record.settings;
    if (!settings.is_shot()) {
      jobs_.push_back(std::move(job));
      check_unique_id(jobs_.back(), id_path(jobs_.back()));
      return;
    }
    settings.shot = job.record.id;
    const int first = settings.first_frame, last = settings.last_frame, size = chunk.value_or(last - first + 1);
    for (int start = first; start <= last; start += size) {
      Job part = job;
      part.record.settings.first_frame = start;
      part.record.settings.last_frame = std::min(last, start + size - 1);
      if (chunk) {
        char suffix[32];
        std::snprintf(suffix, sizeof suffix, ".f%04d-%04d", start, part.record.settings.last_frame);
        part.record.id += suffix;
      }
      jobs_.push_back(std::move(part));
      check_unique_id(jobs_.back(), id_path(jobs_.back()));
    }
  }

  static std::string id_path(const Job& job) { return job.path == "cross" ? job.path : scene::child_path(job.path, "id"); }

  void check_unique_id(const Job& job, const std::string& path) const {
    for (const Job& other : jobs_)
      if (&other != &job && other.record.id == job.record.id)
        reader_.fail(path, "job id '" + job.record.id + "' is already the id of a job of " + other.path);
  }

  void check_references() const {
    for (const Job& job : jobs_) {
      const JobSettings& settings = job.record.settings;
      if (settings.reference_job.empty()) continue;
      const std::string path = job.path == "cross" ? "cross.reference" : scene::child_path(job.path, "reference_job");
      const std::string where = job.path == "cross" ? " (job '" + job.record.id + "')" : "";
      reader_.expect(settings.reference_job != job.record.id, path, "a job cannot be its own reference" + where);
      const Job* reference = nullptr;
      for (const Job& other : jobs_)
        if (other.record.id == settings.reference_job) reference = &other;
      reader_.expect(reference != nullptr, path, "no job has the id '" + settings.reference_job + "'" + where);
      const JobSettings& theirs = reference->record.settings;
      reader_.expect(theirs.width == settings.width && theirs.height == settings.height, path,
                     "'" + settings.reference_job + "' renders " + std::to_string(theirs.width) + "x" +
                         std::to_string(theirs.height) + ", this job " + std::to_string(settings.width) + "x" +
                         std::to_string(settings.height) + "; images compare only at the same size" + where);
    }
  }

  // The job's avsm-capture arguments, checked by the parser avsm-capture runs.
  JobRecord finish_job(Job& job) const {
    const capture::CaptureOptions options = capture_options(job.record.settings);
    try {
      capture::validate_capture_options(options);
    } catch (const capture::UsageError& e) {
      reader_.fail(job.path, "avsm-capture refuses the settings of job '" + job.record.id + "': " + e.what());
    }
    job.record.capture_args = capture::capture_arguments(options);
    job.record.output = job.record.id;
    return job.record;
  }

  Reader reader_;
  fs::path dir_;
  JobSettings defaults_ = capture_defaults();
  std::optional<int> defaults_chunk_;
  std::vector<Job> jobs_;
};

}  // namespace

SweepIndex parse_manifest(std::string_view json_text, const fs::path& file) {
  return ManifestReader(file).read(json_text);
}

SweepIndex read_manifest(const fs::path& file) {
  const std::vector<std::byte> bytes = scene::detail::read_file_bytes(file, kMaxManifestBytes);
  return parse_manifest(std::string_view(reinterpret_cast<const char*>(bytes.data()), bytes.size()), file);
}

capture::CaptureOptions capture_options(const JobSettings& settings) {
  capture::CaptureOptions options;
  if (!settings.scene.empty()) options.scene = settings.scene;
  options.camera = settings.camera;
  options.width = settings.width;
  options.height = settings.height;
  options.frames = settings.frames;
  options.shadow = settings.shadow;
  options.compare_to_uncompressed = settings.compare_to == "uncompressed";
  if (settings.is_shot()) {
    options.frame_range = capture::FrameRange{settings.first_frame, settings.last_frame, settings.fps};
    options.fps = settings.fps;
  }
  return options;
}

}  // namespace avsm::sweep
