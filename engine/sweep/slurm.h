#pragma once
// Running a prepared sweep folder on a Slurm cluster: one `sbatch --array` job whose
// task I runs `avsm-sweep task DIR --index I` (job I of the manifest), and reading
// the results back (each job's job.json, and Slurm's squeue/sacct for tasks that
// have not written a final one). DIR must be on storage every node mounts at the
// same path. Files: DIR/slurm/sweep.sbatch, DIR/slurm/slurm.json, DIR/slurm/task-I.log.
#include <nlohmann/json_fwd.hpp>

#include <chrono>
#include <cstddef>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "sweep/sweep_index.h"

namespace avsm::sweep {

// The cluster-specific requests; empty means the cluster's default.
struct SlurmOptions {
  std::string partition;                 // --partition
  std::string time;                      // --time, e.g. 00:30:00
  std::string mem;                       // --mem, e.g. 8G
  std::string gres;                      // --gres, e.g. gpu:1
  std::vector<std::string> sbatch_args;  // passed on as written, e.g. --account=render
  bool force = false;                    // tasks run their job even when it is done (task --force)
};

// What DIR/slurm/slurm.json records about the submission.
struct SlurmSubmission {
  std::string job_id;          // the array's Slurm job id
  std::vector<size_t> tasks;   // the array task ids submitted (= job indices)
  std::string script;          // the sbatch script, absolute

  bool operator==(const SlurmSubmission&) const = default;
};

nlohmann::json to_json(const SlurmSubmission& submission);
SlurmSubmission slurm_submission_from_json(const nlohmann::json& in);

std::filesystem::path slurm_dir(const std::filesystem::path& sweep_dir);
std::filesystem::path slurm_submission_path(const std::filesystem::path& sweep_dir);
std::filesystem::path slurm_task_log_path(const std::filesystem::path& sweep_dir, size_t task);
// nullopt when DIR was never submitted to Slurm (no DIR/slurm/slurm.json).
std::optional<SlurmSubmission> read_slurm_submission(const std::filesystem::path& sweep_dir);

// The sbatch script: commented for a cluster's admin, one array task per index in
// `tasks`, each running `sweep_binary task sweep_dir --index $SLURM_ARRAY_TASK_ID`.
// Both paths must be absolute (the nodes run the script from another machine).
std::string sbatch_script(const std::filesystem::path& sweep_dir, const std::filesystem::path& sweep_binary,
                          const std::vector<size_t>& tasks, const SlurmOptions& options);

// "0-3" or "0,2,5-7": the --array value for these task ids (sorted, unique).
std::string array_spec(const std::vector<size_t>& tasks);

// Writes DIR/slurm/sweep.sbatch, submits it with `sbatch --parsable` and records
// DIR/slurm/slurm.json. Throws std::runtime_error when sbatch is missing or refuses,
// quoting Slurm's message and naming the setting to change.
SlurmSubmission submit_to_slurm(const std::filesystem::path& sweep_dir, const std::filesystem::path& sweep_binary,
                                const std::vector<size_t>& tasks, const SlurmOptions& options);

// `avsm-sweep slurm`: prepares DIR from the manifest (prepare_sweep), marks the jobs
// to run pending (those not done, or all with options.force), and submits them. Refuses while
// an earlier submission of DIR still has tasks queued or running, so no job runs twice
// at once. `sweep_binary`: the avsm-sweep the tasks run (absolute). nullopt when every
// job is done already (nothing submitted).
std::optional<SlurmSubmission> prepare_and_submit_to_slurm(const std::filesystem::path& manifest,
                                                           const std::filesystem::path& sweep_dir,
                                                           const std::filesystem::path& sweep_binary,
                                                           const SlurmOptions& options);

// For sbatch's error message, the avsm-sweep option or slurm.conf setting that
// usually fixes it; empty when the message is not one we know.
std::string sbatch_error_hint(const std::string& message);

// Slurm's state of each submitted task it still knows about, by task id, e.g.
// PENDING, RUNNING, COMPLETED, FAILED, TIMEOUT, CANCELLED: squeue first (queued,
// running and recently finished tasks), then sacct for the rest where the cluster
// keeps accounting. A task missing from the map is one Slurm no longer reports.
// Throws when squeue itself cannot be run or reach the controller.
std::map<size_t, std::string> slurm_task_states(const SlurmSubmission& submission);

// True for the states of a task Slurm has not finished with (queued, running, completing...).
bool is_active_slurm_state(const std::string& state);

// DIR/index.json rebuilt from the job.json files (collect), with Slurm's view added:
// a submitted job Slurm still has queued or running is pending/running, and one whose
// task ended without writing a final job.json (killed at its time limit, cancelled,
// node lost) is failed with an error naming the task, its Slurm state and its log;
// that failure is written to its job.json too, so index.json and a later collect agree.
SweepIndex collect_with_slurm(const std::filesystem::path& sweep_dir);

// Polls collect_with_slurm until no submitted task is pending or running, or until
// `timeout` passes. Returns the last index (collect's when DIR was not submitted).
SweepIndex wait_for_slurm(const std::filesystem::path& sweep_dir, std::chrono::seconds timeout);

}  // namespace avsm::sweep
