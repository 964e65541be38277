#pragma once
// A sweep's job index: what DIR/index.json and each DIR/<job id>/job.json hold
// (the sweep folder layout is described in docs/farm.md).
// One writer (to_json) and one reader (from_json) per type; the reader's errors name
// the key, and the file readers prefix the file.
#include <nlohmann/json_fwd.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <vector>

#include "scene/light.h"

namespace avsm::sweep {

enum class JobStatus { pending, running, done, failed };

std::string_view to_string(JobStatus status);
std::optional<JobStatus> job_status_from_string(std::string_view text);

// One job's settings as the manifest chose them (after the cross product and the
// manifest's defaults): what avsm-capture is run with, plus what to compare against.
struct JobSettings {
  std::string scene;   // absolute path; empty: avsm-capture's default scene
  std::string camera;  // name or index; empty: the scene's first camera
  uint32_t width = 1280;
  uint32_t height = 720;
  uint32_t frames = 5;
  scene::ShadowOverrides shadow;  // only the overrides set are written
  std::string compare_to;         // "uncompressed" or empty (no quality.json)
  std::string reference_job;      // the id of the job whose frame.exr this one is compared to; may be empty
  // A shot (avsm-capture --frame-range): frames first_frame..last_frame at fps; -1: one
  // instant. `shot` names the shot a chunk renders part of (the manifest job's id).
  int first_frame = -1, last_frame = -1;
  float fps = 24.0f;
  std::string shot;

  bool is_shot() const { return first_frame >= 0; }
  bool operator==(const JobSettings&) const = default;
};

struct JobRecord {
  std::string id;  // [A-Za-z0-9._-]+, unique in the sweep; the job's folder name
  JobSettings settings;
  std::vector<std::string> capture_args;  // exactly what avsm-capture runs with, minus --out
  JobStatus status = JobStatus::pending;
  std::optional<int> exit_code;  // unset until the job finished
  std::string error;             // when failed: the capture's last error line(s)
  std::string output;            // the job's folder, relative to the sweep folder
  double wall_s = 0.0;           // the only timing in the index

  bool operator==(const JobRecord&) const = default;
};

// A shot split into chunks (one job, one Slurm array task each), merged: its frames in
// order, each with the chunk that rendered it and its image (relative to the sweep
// folder). Timings stay in each chunk's shot.json, so that two runs index alike.
struct ShotFrameIndex {
  int frame = 0;
  float time = 0.0f;
  std::string job;
  std::string image;

  bool operator==(const ShotFrameIndex&) const = default;
};

struct ShotIndex {
  std::string id;
  int first_frame = 0, last_frame = 0;
  float fps = 24.0f;
  std::vector<std::string> chunks;     // job ids, in frame order
  std::vector<ShotFrameIndex> frames;  // those rendered so far (chunks done)

  bool complete() const { return frames.size() == std::size_t(last_frame - first_frame + 1); }
  bool operator==(const ShotIndex&) const = default;
};

struct SweepIndex {
  std::string manifest;  // absolute path of the original manifest
  std::vector<JobRecord> jobs;  // manifest order
  std::vector<ShotIndex> shots;  // the shots among the jobs, merged by collect()

  bool operator==(const SweepIndex&) const = default;
  const JobRecord* find(std::string_view id) const;
};

// True for a usable job id: [A-Za-z0-9._-]+, and not ".", "..", or a name the sweep
// folder uses itself (slurm, manifest.json, index.json, report.html).
bool is_valid_job_id(std::string_view id);

nlohmann::json to_json(const scene::ShadowOverrides& shadow);
scene::ShadowOverrides shadow_overrides_from_json(const nlohmann::json& in);
nlohmann::json to_json(const JobSettings& settings);
JobSettings job_settings_from_json(const nlohmann::json& in);
nlohmann::json to_json(const JobRecord& job);
JobRecord job_record_from_json(const nlohmann::json& in);
nlohmann::json to_json(const ShotIndex& shot);
ShotIndex shot_index_from_json(const nlohmann::json& in);
nlohmann::json to_json(const SweepIndex& index);
SweepIndex sweep_index_from_json(const nlohmann::json& in);

// The files of a sweep folder. Writes are atomic (a temporary file renamed over the
// old one), so a reader never sees half a file even while jobs finish around it.
// Errors throw std::runtime_error naming the file.
std::filesystem::path index_file(const std::filesystem::path& sweep_dir);
std::filesystem::path job_file(const std::filesystem::path& sweep_dir, const std::string& job_id);
SweepIndex read_index(const std::filesystem::path& sweep_dir);
void write_index(const std::filesystem::path& sweep_dir, const SweepIndex& index);
// nullopt when the job has no job.json yet (it has not started).
std::optional<JobRecord> read_job_record(const std::filesystem::path& sweep_dir, const std::string& job_id);
void write_job_record(const std::filesystem::path& sweep_dir, const JobRecord& job);

// Rebuilds DIR/index.json from DIR/<id>/job.json: the index's job list (written when
// the sweep was prepared) with every job that has a job.json replaced by it, and its
// shots merged from their chunks' shot.json. Returns what it wrote. Throws naming the
// file when a job.json is not the job of its folder.
SweepIndex collect(const std::filesystem::path& sweep_dir);

}  // namespace avsm::sweep
