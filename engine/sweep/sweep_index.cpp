#include "sweep/sweep_index.h"

#include <unistd.h>

#include <algorithm>
#include <cctype>

#include <nlohmann/json.hpp>
#include <stdexcept>

#include "capture/files.h"
#include "capture/json_read.h"

namespace avsm::sweep {
namespace fs = std::filesystem;
using capture::array_of;
using capture::member;
using capture::value_of;
using nlohmann::json;

namespace {

// What the sweep folder holds besides the job folders.
constexpr std::string_view kReservedNames[] = {"slurm", "manifest.json", "index.json", "report.html"};

constexpr std::string_view kStatusNames[] = {"pending", "running", "done", "failed"};

template <class Enum>
Enum choice_of(const json& object, const char* key, std::optional<Enum> (*from_string)(std::string_view)) {
  const std::string name = value_of<std::string>(object, key);
  if (std::optional<Enum> value = from_string(name)) return *value;
  throw std::runtime_error(std::string("\"") + key + "\": unknown value '" + name + "'");
}

// Writes next to `path` and renames over it: readers (status, collect, a Slurm task's
// neighbours) see the old file or the new one, never a partial one.
void write_json_atomically(const fs::path& path, const json& content) {
  const fs::path temporary = path.string() + ".tmp" + std::to_string(::getpid());
  capture::write_json(temporary, content);
  std::error_code ec;
  fs::rename(temporary, path, ec);
  if (ec) throw std::runtime_error(path.string() + ": cannot write (" + ec.message() + ")");
}

}  // namespace

std::string_view to_string(JobStatus status) { return kStatusNames[size_t(status)]; }

std::optional<JobStatus> job_status_from_string(std::string_view text) {
  for (size_t i = 0; i < std::size(kStatusNames); ++i)
    if (kStatusNames[i] == text) return JobStatus(i);
  return std::nullopt;
}

const JobRecord* SweepIndex::find(std::string_view id) const {
  for (const JobRecord& job : jobs)
    if (job.id == id) return &job;
  return nullptr;
}

bool is_valid_job_id(std::string_view id) {
  if (id.empty() || id == "." || id == "..") return false;
  for (std::string_view reserved : kReservedNames)
    if (id == reserved) return false;
  for (char c : id)
    if (!std::isalnum(static_cast<unsigned char>(c)) && c != '.' && c != '_' && c != '-') return false;
  return true;
}

// ---- JSON ----

json to_json(const scene::ShadowOverrides& shadow) {
  json out = json::object();
  if (shadow.technique) out["technique"] = *shadow.technique;
  if (shadow.nodes) out["nodes"] = *shadow.nodes;
  if (shadow.resolution) out["resolution"] = *shadow.resolution;
  if (shadow.filter) out["filter"] = scene::to_string(*shadow.filter);
  if (shadow.kernel) out["kernel"] = scene::to_string(*shadow.kernel);
  if (shadow.kernel_radius) out["kernel_radius"] = *shadow.kernel_radius;
  if (shadow.sort) out["sort"] = *shadow.sort;
  if (shadow.build) out["build"] = scene::to_string(*shadow.build);
  if (shadow.fit) out["fit"] = scene::to_string(*shadow.fit);
  if (shadow.cascades) out["cascades"] = *shadow.cascades;
  if (shadow.clusters) out["clusters"] = *shadow.clusters;
  if (shadow.layout) out["layout"] = scene::to_string(*shadow.layout);
  if (shadow.virtual_resolution) out["virtual_resolution"] = *shadow.virtual_resolution;
  if (shadow.page_size) out["page_size"] = *shadow.page_size;
  if (shadow.virtual_lights) out["virtual_lights"] = *shadow.virtual_lights;
  if (shadow.page_pool_mib) out["page_pool_mib"] = *shadow.page_pool_mib;
  if (shadow.page_lod_bias) out["page_lod_bias"] = *shadow.page_lod_bias;
  if (shadow.page_volume_lod_bias) out["page_volume_lod_bias"] = *shadow.page_volume_lod_bias;
  if (shadow.page_builds_per_frame) out["page_builds_per_frame"] = *shadow.page_builds_per_frame;
  if (!shadow.parameters.empty()) out["parameters"] = shadow.parameters;
  return out;
}

scene::ShadowOverrides shadow_overrides_from_json(const json& in) {
  if (!in.is_object()) throw std::runtime_error("expected an object of shadow overrides");
  scene::ShadowOverrides shadow;
  if (in.contains("technique")) shadow.technique = value_of<std::string>(in, "technique");
  if (in.contains("nodes")) shadow.nodes = value_of<int>(in, "nodes");
  if (in.contains("resolution")) shadow.resolution = value_of<int>(in, "resolution");
  if (in.contains("filter")) shadow.filter = choice_of(in, "filter", scene::shadow_filter_from_string);
  if (in.contains("kernel")) shadow.kernel = choice_of(in, "kernel", scene::shadow_kernel_from_string);
  if (in.contains("kernel_radius")) shadow.kernel_radius = value_of<int>(in, "kernel_radius");
  if (in.contains("sort")) shadow.sort = value_of<bool>(in, "sort");
  if (in.contains("build")) shadow.build = choice_of(in, "build", scene::shadow_build_from_string);
  if (in.contains("fit")) shadow.fit = choice_of(in, "fit", scene::shadow_fit_from_string);
  if (in.contains("cascades")) shadow.cascades = value_of<int>(in, "cascades");
  if (in.contains("clusters")) shadow.clusters = value_of<int>(in, "clusters");
  if (in.contains("layout")) shadow.layout = choice_of(in, "layout", scene::shadow_layout_from_string);
  if (in.contains("virtual_resolution")) shadow.virtual_resolution = value_of<int>(in, "virtual_resolution");
  if (in.contains("page_size")) shadow.page_size = value_of<int>(in, "page_size");
  if (in.contains("virtual_lights")) shadow.virtual_lights = value_of<int>(in, "virtual_lights");
  if (in.contains("page_pool_mib")) shadow.page_pool_mib = value_of<double>(in, "page_pool_mib");
  if (in.contains("page_lod_bias")) shadow.page_lod_bias = value_of<float>(in, "page_lod_bias");
  if (in.contains("page_volume_lod_bias")) shadow.page_volume_lod_bias = value_of<float>(in, "page_volume_lod_bias");
  if (in.contains("page_builds_per_frame")) shadow.page_builds_per_frame = value_of<int>(in, "page_builds_per_frame");
  if (in.contains("parameters")) shadow.parameters = value_of<std::map<std::string, double>>(in, "parameters");
  return shadow;
}

json to_json(const JobSettings& s) {
  json out = {{"scene", s.scene},   {"camera", s.camera},         {"width", s.width},
              {"height", s.height}, {"frames", s.frames},         {"shadow", to_json(s.shadow)},
              {"compare_to", s.compare_to}, {"reference_job", s.reference_job}};
  if (s.is_shot()) out["shot"] = {{"id", s.shot}, {"first_frame", s.first_frame}, {"last_frame", s.last_frame}, {"fps", s.fps}};
  return out;
}

JobSettings job_settings_from_json(const json& in) {
  JobSettings s;
  s.scene = value_of<std::string>(in, "scene");
  s.camera = value_of<std::string>(in, "camera");
  s.width = value_of<uint32_t>(in, "width");
  s.height = value_of<uint32_t>(in, "height");
  s.frames = value_of<uint32_t>(in, "frames");
  try {
    s.shadow = shadow_overrides_from_json(member(in, "shadow"));
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("shadow: ") + e.what());
  }
  s.compare_to = value_of<std::string>(in, "compare_to");
  s.reference_job = value_of<std::string>(in, "reference_job");
  if (in.contains("shot")) {  // absent for one instant (and in indexes written before shots)
    const json& shot = member(in, "shot");
    s.shot = value_of<std::string>(shot, "id");
    s.first_frame = value_of<int>(shot, "first_frame");
    s.last_frame = value_of<int>(shot, "last_frame");
    s.fps = value_of<float>(shot, "fps");
  }
  return s;
}

json to_json(const JobRecord& job) {
  return {{"id", job.id},
          {"settings", to_json(job.settings)},
          {"capture_args", job.capture_args},
          {"status", to_string(job.status)},
          {"exit_code", job.exit_code ? json(*job.exit_code) : json(nullptr)},
          {"error", job.error},
          {"output", job.output},
          {"wall_s", job.wall_s}};
}

JobRecord job_record_from_json(const json& in) {
  JobRecord job;
  job.id = value_of<std::string>(in, "id");
  if (!is_valid_job_id(job.id)) throw std::runtime_error("\"id\": '" + job.id + "' is not a job id ([A-Za-z0-9._-]+)");
  try {
    job.settings = job_settings_from_json(member(in, "settings"));
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(std::string("settings: ") + e.what());
  }
  job.capture_args = value_of<std::vector<std::string>>(in, "capture_args");
  job.status = choice_of(in, "status", job_status_from_string);
  if (const json& code = member(in, "exit_code"); !code.is_null()) job.exit_code = value_of<int>(in, "exit_code");
  job.error = value_of<std::string>(in, "error");
  job.output = value_of<std::string>(in, "output");
  // A folder inside the sweep's (the runner empties it before the job runs).
  if (!is_valid_job_id(job.output)) throw std::runtime_error("\"output\": '" + job.output + "' is not a job folder");
  job.wall_s = value_of<double>(in, "wall_s");
  return job;
}

json to_json(const ShotIndex& shot) {
  json frames = json::array();
  for (const ShotFrameIndex& f : shot.frames)
    frames.push_back({{"frame", f.frame}, {"time", f.time}, {"job", f.job}, {"image", f.image}});
  return {{"id", shot.id},         {"first_frame", shot.first_frame}, {"last_frame", shot.last_frame},
          {"fps", shot.fps},       {"chunks", shot.chunks},           {"complete", shot.complete()},
          {"frames", frames}};
}

ShotIndex shot_index_from_json(const json& in) {
  ShotIndex shot;
  shot.id = value_of<std::string>(in, "id");
  shot.first_frame = value_of<int>(in, "first_frame");
  shot.last_frame = value_of<int>(in, "last_frame");
  shot.fps = value_of<float>(in, "fps");
  shot.chunks = value_of<std::vector<std::string>>(in, "chunks");
  shot.frames = array_of<ShotFrameIndex>(in, "frames", [](const json& f) {
    return ShotFrameIndex{value_of<int>(f, "frame"), value_of<float>(f, "time"), value_of<std::string>(f, "job"),
                          value_of<std::string>(f, "image")};
  });
  return shot;
}

json to_json(const SweepIndex& index) {
  json jobs = json::array(), shots = json::array();
  for (const JobRecord& job : index.jobs) jobs.push_back(to_json(job));
  for (const ShotIndex& shot : index.shots) shots.push_back(to_json(shot));
  return {{"manifest", index.manifest}, {"jobs", jobs}, {"shots", shots}};
}

SweepIndex sweep_index_from_json(const json& in) {
  SweepIndex index{value_of<std::string>(in, "manifest"), array_of<JobRecord>(in, "jobs", job_record_from_json), {}};
  if (in.contains("shots")) index.shots = array_of<ShotIndex>(in, "shots", shot_index_from_json);
  return index;
}

// ---- files ----

fs::path index_file(const fs::path& sweep_dir) { return sweep_dir / "index.json"; }

fs::path job_file(const fs::path& sweep_dir, const std::string& job_id) {
  return sweep_dir / job_id / "job.json";
}

SweepIndex read_index(const fs::path& sweep_dir) {
  return capture::read_report_file(index_file(sweep_dir), sweep_index_from_json);
}

void write_index(const fs::path& sweep_dir, const SweepIndex& index) {
  write_json_atomically(index_file(sweep_dir), to_json(index));
}

std::optional<JobRecord> read_job_record(const fs::path& sweep_dir, const std::string& job_id) {
  const fs::path path = job_file(sweep_dir, job_id);
  std::error_code ec;
  if (!fs::exists(path, ec)) return std::nullopt;
  JobRecord job = capture::read_report_file(path, job_record_from_json);
  if (job.id != job_id)
    throw std::runtime_error(path.string() + ": holds job '" + job.id + "', not '" + job_id + "' of its folder");
  return job;
}

void write_job_record(const fs::path& sweep_dir, const JobRecord& job) {
  std::error_code ec;
  fs::create_directories(sweep_dir / job.id, ec);
  if (ec) throw std::runtime_error((sweep_dir / job.id).string() + ": cannot create (" + ec.message() + ")");
  write_json_atomically(job_file(sweep_dir, job.id), to_json(job));
}

namespace {

// The shots among the jobs, each merged from its done chunks' shot.json (frame order).
std::vector<ShotIndex> merge_shots(const fs::path& sweep_dir, const std::vector<JobRecord>& jobs) {
  std::vector<ShotIndex> shots;
  for (const JobRecord& job : jobs) {
    const JobSettings& s = job.settings;
    if (!s.is_shot()) continue;
    auto shot = std::find_if(shots.begin(), shots.end(), [&](const ShotIndex& x) { return x.id == s.shot; });
    if (shot == shots.end()) shot = shots.insert(shots.end(), ShotIndex{s.shot, s.first_frame, s.last_frame, s.fps, {}, {}});
    shot->first_frame = std::min(shot->first_frame, s.first_frame);
    shot->last_frame = std::max(shot->last_frame, s.last_frame);
    shot->chunks.push_back(job.id);
    if (job.status != JobStatus::done) continue;
    const json chunk = capture::read_report_file(sweep_dir / job.output / "shot.json", +[](const json& in) { return in; });
    for (const json& frame : member(chunk, "frames"))
      shot->frames.push_back({value_of<int>(frame, "frame"), value_of<float>(frame, "time"), job.id,
                              (fs::path(job.output) / value_of<std::string>(frame, "image")).generic_string()});
  }
  for (ShotIndex& shot : shots)
    std::sort(shot.frames.begin(), shot.frames.end(), [](const ShotFrameIndex& a, const ShotFrameIndex& b) { return a.frame < b.frame; });
  return shots;
}

}  // namespace

SweepIndex collect(const fs::path& sweep_dir) {
  SweepIndex index = read_index(sweep_dir);
  for (JobRecord& job : index.jobs)
    if (std::optional<JobRecord> record = read_job_record(sweep_dir, job.id)) job = std::move(*record);
  index.shots = merge_shots(sweep_dir, index.jobs);
  write_index(sweep_dir, index);
  return index;
}

}  // namespace avsm::sweep
