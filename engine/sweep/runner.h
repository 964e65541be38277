#pragma once
// Running a sweep: preparing its folder from a manifest, running one job (what a local
// run does for each job and what a Slurm array task calls) and running them all locally.
// Each job is avsm-capture as a child process, so a job that crashes takes only itself
// down; its output goes to DIR/<id>/log.txt and its result to DIR/<id>/job.json.
#include <filesystem>
#include <functional>

#include "sweep/sweep_index.h"

namespace avsm::sweep {

// $AVSM_CAPTURE if set, else the avsm-capture next to the running executable. Throws
// naming the path when it is not an executable file.
std::filesystem::path find_capture_executable();

// Validates the manifest (errors: scene::LoadError naming it and the JSON path), copies
// it to DIR/manifest.json and writes DIR/index.json. A job whose job.json is of other
// settings than the manifest's now loses it (the job runs again); one of the same
// settings keeps its result, so a finished job stays finished.
SweepIndex prepare_sweep(const std::filesystem::path& manifest, const std::filesystem::path& sweep_dir);

struct JobRunOptions {
  std::filesystem::path capture;  // avsm-capture
  bool force = false;             // run jobs whose job.json says done too
};

struct JobRun {
  JobRecord record;
  bool skipped = false;  // already done (and not forced)
};

// Runs job `index` (manifest order) of a prepared sweep: job.json says running, then
// done or failed with the exit code, the capture's error and the wall time. The job's
// folder is emptied first, so it holds this run's files only.
JobRun run_job(const std::filesystem::path& sweep_dir, size_t index, const JobRunOptions& options);

struct SweepRunOptions {
  JobRunOptions job;
  unsigned parallel_jobs = 1;
  std::function<void(const JobRun&)> on_job_finished;  // called one at a time
};

// Runs every job of a prepared sweep, `parallel_jobs` at once; a failed job does not
// stop the others. Returns collect(sweep_dir) once all have finished.
SweepIndex run_sweep(const std::filesystem::path& sweep_dir, const SweepRunOptions& options);

}  // namespace avsm::sweep
