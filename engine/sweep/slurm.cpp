#include "sweep/slurm.h"

#include <nlohmann/json.hpp>

#include <algorithm>
#include <array>
#include <cerrno>
#include <cstring>
#include <sstream>
#include <stdexcept>
#include <thread>

#include "capture/files.h"
#include "capture/json_read.h"
#include "capture/run_command.h"
#include "sweep/runner.h"

namespace avsm::sweep {

using capture::CommandResult;
using capture::run_command;
namespace fs = std::filesystem;
using capture::value_of;

namespace {

std::string trimmed(const std::string& text) {
  const size_t begin = text.find_first_not_of(" \t\r\n");
  if (begin == std::string::npos) return "";
  const size_t end = text.find_last_not_of(" \t\r\n");
  return text.substr(begin, end - begin + 1);
}

std::string one_line(const std::string& text) {
  std::string line = trimmed(text);
  std::replace(line.begin(), line.end(), '\n', ' ');
  return line;
}

// A word for a shell script: single-quoted, with any ' closed, escaped and reopened.
std::string shell_quoted(const std::string& word) {
  std::string quoted = "'";
  for (char c : word) quoted += c == '\'' ? std::string("'\\''") : std::string(1, c);
  return quoted + "'";
}

// A path on an #SBATCH line: sbatch splits those lines at spaces unless quoted.
std::string sbatch_quoted(const fs::path& path) {
  const std::string text = path.string();
  if (text.find('"') != std::string::npos) {
    throw std::runtime_error("'" + text + "': a sweep folder for Slurm cannot have a '\"' in its path; choose another --out");
  }
  return "\"" + text + "\"";
}

// An #SBATCH request: set when the option was given, otherwise a disabled (##) line
// showing an example, so the admin sees where it goes.
std::string request_line(const std::string& flag, const std::string& value, const std::string& example,
                         const std::string& why) {
  const std::string line = value.empty() ? "##SBATCH " + flag + "=" + example : "#SBATCH " + flag + "=" + value;
  return line + std::string(std::max<size_t>(1, 36 - std::min<size_t>(line.size(), 35)), ' ') + "# " + why + "\n";
}

// One line of `squeue --format=%K|%T` or `sacct --format=JobID,State`: task id and state.
struct TaskState {
  size_t task = 0;
  std::string state;
};

std::optional<size_t> parse_task_id(const std::string& text) {
  if (text.empty() || text.find_first_not_of("0123456789") != std::string::npos) return std::nullopt;
  return std::stoul(text);
}

// squeue: the tasks the controller still lists (queued, running, or finished less
// than MinJobAge seconds ago). A job it has forgotten is an empty map, not an error.
std::map<size_t, std::string> squeue_task_states(const std::string& job_id) {
  const std::optional<CommandResult> result = run_command(
      {"squeue", "--noheader", "--array", "--states=all", "--jobs=" + job_id, "--format=%K|%T"});
  if (!result) {
    throw std::runtime_error("squeue is not installed: reading the state of Slurm job " + job_id +
                             " needs Slurm's client commands (slurm-client; tools/install-deps.sh installs slurm-wlm)");
  }
  if (result->exit_code != 0) {
    if (result->err.find("Invalid job id") != std::string::npos) return {};
    throw std::runtime_error("squeue failed for Slurm job " + job_id + ": '" + one_line(result->err) +
                             "'; check that slurmctld is up and SLURM_CONF names this cluster's slurm.conf");
  }
  std::map<size_t, std::string> states;
  std::istringstream lines(result->out);
  for (std::string line; std::getline(lines, line);) {
    const size_t bar = line.find('|');
    if (bar == std::string::npos) continue;
    if (const auto task = parse_task_id(trimmed(line.substr(0, bar)))) states[*task] = trimmed(line.substr(bar + 1));
  }
  return states;
}

// sacct: finished tasks, where the cluster keeps accounting (slurmdbd). Says nothing
// (an empty map) where it cannot answer, e.g. "Slurm accounting storage is disabled".
std::map<size_t, std::string> sacct_task_states(const std::string& job_id) {
  const std::optional<CommandResult> result = run_command(
      {"sacct", "--noheader", "--parsable2", "--allocations", "--jobs=" + job_id, "--format=JobID,State"});
  std::map<size_t, std::string> states;
  if (!result || result->exit_code != 0) return states;
  const std::string prefix = job_id + "_";
  std::istringstream lines(result->out);
  for (std::string line; std::getline(lines, line);) {
    const size_t bar = line.find('|');
    if (bar == std::string::npos || line.compare(0, prefix.size(), prefix) != 0) continue;
    const auto task = parse_task_id(line.substr(prefix.size(), bar - prefix.size()));
    std::string state = trimmed(line.substr(bar + 1));
    state = state.substr(0, state.find(' '));  // "CANCELLED by 0"
    if (task) states[*task] = state;
  }
  return states;
}

bool is_finished(JobStatus status) { return status == JobStatus::done || status == JobStatus::failed; }

}  // namespace

nlohmann::json to_json(const SlurmSubmission& submission) {
  return {{"job_id", submission.job_id}, {"tasks", submission.tasks}, {"script", submission.script}};
}

SlurmSubmission slurm_submission_from_json(const nlohmann::json& in) {
  SlurmSubmission submission;
  submission.job_id = value_of<std::string>(in, "job_id");
  submission.tasks = value_of<std::vector<size_t>>(in, "tasks");
  submission.script = value_of<std::string>(in, "script");
  return submission;
}

fs::path slurm_dir(const fs::path& sweep_dir) { return sweep_dir / "slurm"; }
fs::path slurm_submission_path(const fs::path& sweep_dir) { return slurm_dir(sweep_dir) / "slurm.json"; }
fs::path slurm_task_log_path(const fs::path& sweep_dir, size_t task) {
  return slurm_dir(sweep_dir) / ("task-" + std::to_string(task) + ".log");
}

std::optional<SlurmSubmission> read_slurm_submission(const fs::path& sweep_dir) {
  const fs::path path = slurm_submission_path(sweep_dir);
  if (!fs::exists(path)) return std::nullopt;
  return capture::read_report_file(path, &slurm_submission_from_json);
}

std::string array_spec(const std::vector<size_t>& tasks) {
  std::vector<size_t> sorted = tasks;
  std::sort(sorted.begin(), sorted.end());
  sorted.erase(std::unique(sorted.begin(), sorted.end()), sorted.end());
  std::string spec;
  for (size_t i = 0; i < sorted.size();) {
    size_t last = i;
    while (last + 1 < sorted.size() && sorted[last + 1] == sorted[last] + 1) ++last;
    if (!spec.empty()) spec += ',';
    spec += std::to_string(sorted[i]);
    if (last > i) spec.append(1, '-').append(std::to_string(sorted[last]));
    i = last + 1;
  }
  return spec;
}

std::string sbatch_script(const fs::path& sweep_dir, const fs::path& sweep_binary, const std::vector<size_t>& tasks,
                          const SlurmOptions& options) {
  if (!sweep_dir.is_absolute() || !sweep_binary.is_absolute()) {
    throw std::logic_error("sbatch_script needs absolute paths");
  }
  if (tasks.empty()) throw std::runtime_error(sweep_dir.string() + ": no jobs to submit to Slurm");
  std::ostringstream s;
  s << "#!/bin/bash\n"
       "# A sweep of avsm-capture jobs as one Slurm job array, written by `avsm-sweep slurm`.\n"
       "# Array task I runs job I of the sweep (manifest order): it renders into\n"
       "# " << sweep_dir.string() << "/<job id>/ and writes that folder's job.json.\n"
       "# Submit again (e.g. after editing it for your cluster) with: sbatch " << (slurm_dir(sweep_dir) / "sweep.sbatch").string() << "\n"
       "#\n"
       "# What to change for your cluster (or pass the avsm-sweep slurm option named):\n"
       "#  - the partition (queue) of nodes that can render (--partition);\n"
       "#  - the GPU request: --gres=gpu:1 gives each task one GPU; a capture renders on one (--gres);\n"
       "#  - the time and memory limits of one task (--time, --mem);\n"
       "#  - anything else your site requires, e.g. --account or --qos (--sbatch-arg);\n"
       "#  - the sweep folder must be on storage every node mounts at this same path (NFS, Lustre, ...);\n"
       "#  - avsm-sweep and avsm-capture must be installed at this same path on every node (set\n"
       "#    AVSM_CAPTURE to use an avsm-capture elsewhere). The job inherits the submitting\n"
       "#    shell's environment (sbatch's default --export=ALL).\n"
       "# Lines starting with ##SBATCH are disabled examples; remove one # to enable one.\n"
       "#SBATCH --job-name=avsm-sweep\n"
       "#SBATCH --array=" << array_spec(tasks) << "             # one task per sweep job (job index = task id)\n"
       "#SBATCH --output=" << sbatch_quoted(slurm_dir(sweep_dir) / "task-%a.log") << "\n"
       "#SBATCH --chdir=" << sbatch_quoted(sweep_dir) << "\n"
       "#SBATCH --ntasks=1\n"
    << request_line("--partition", options.partition, "gpu", "the partition (queue) to run in")
    << request_line("--gres", options.gres, "gpu:1", "one GPU per task")
    << request_line("--time", options.time, "00:30:00", "the limit for one capture")
    << request_line("--mem", options.mem, "8G", "memory for one capture")
    << "##SBATCH --cpus-per-task=4          # more CPU threads (CPU rendering with lavapipe)\n";
  for (const std::string& arg : options.sbatch_args) s << "#SBATCH " << arg << "\n";
  s << "\n"
       "exec " << shell_quoted(sweep_binary.string()) << " task " << shell_quoted(sweep_dir.string())
    << " --index \"$SLURM_ARRAY_TASK_ID\"" << (options.force ? " --force" : "") << "\n";
  return s.str();
}

std::string sbatch_error_hint(const std::string& message) {
  struct Hint {
    const char* says;  // matched case-insensitively
    const char* change;
  };
  static const Hint hints[] = {
      {"invalid partition", "--partition (sinfo lists the partitions)"},
      {"gres", "--gres (e.g. gpu:1; `sinfo -o \"%P %G\"` lists what each partition's nodes offer)"},
      {"--time", "--time (e.g. 00:30:00, within the partition's MaxTime)"},
      {"time limit", "--time (e.g. 00:30:00, within the partition's MaxTime)"},
      {"memory specification", "--mem (at most a node's memory; `sinfo -o \"%P %m\"` lists it in MB)"},
      {"job array", "the sweep has more jobs than the cluster's MaxArraySize (slurm.conf); split the manifest"},
      {"unable to contact slurm controller",
       "the cluster: is slurmctld up, and does SLURM_CONF (or /etc/slurm/slurm.conf) describe it?"},
      {"account", "--sbatch-arg --account=NAME (sacctmgr show assoc user=$USER lists yours)"},
      {"qos", "--sbatch-arg --qos=NAME"},
      {"requested node configuration is not available",
       "--mem, --gres or --sbatch-arg: they ask for more than any node of the partition has"},
  };
  std::string lower = message;
  std::transform(lower.begin(), lower.end(), lower.begin(), [](unsigned char c) { return char(std::tolower(c)); });
  for (const Hint& hint : hints) {
    if (lower.find(hint.says) != std::string::npos) return hint.change;
  }
  return "";
}

SlurmSubmission submit_to_slurm(const fs::path& sweep_dir, const fs::path& sweep_binary, const std::vector<size_t>& tasks,
                                const SlurmOptions& options) {
  fs::create_directories(slurm_dir(sweep_dir));
  SlurmSubmission submission;
  submission.tasks = tasks;
  submission.script = (slurm_dir(sweep_dir) / "sweep.sbatch").string();
  capture::write_text(submission.script, sbatch_script(sweep_dir, sweep_binary, tasks, options));

  const std::optional<CommandResult> result = run_command({"sbatch", "--parsable", submission.script});
  if (!result) {
    throw std::runtime_error("sbatch is not installed here: `avsm-sweep slurm` submits through Slurm's sbatch; run it on a "
                             "machine of the cluster (a login node) or install Slurm's client commands (slurm-client). "
                             "The script is written: " + submission.script);
  }
  if (result->exit_code != 0) {
    const std::string message = one_line(result->err.empty() ? result->out : result->err);
    const std::string hint = sbatch_error_hint(message);
    throw std::runtime_error("sbatch refused " + submission.script + ": '" + message + "'; " +
                             (hint.empty() ? "check the options (--partition, --time, --mem, --gres, --sbatch-arg) or the "
                                             "#SBATCH lines of the script"
                                           : "change " + hint));
  }
  // --parsable prints "JOBID" or "JOBID;CLUSTER".
  submission.job_id = trimmed(result->out.substr(0, result->out.find(';')));
  if (!parse_task_id(submission.job_id)) {
    throw std::runtime_error("sbatch accepted " + submission.script + " but printed '" + one_line(result->out) +
                             "', not a job id");
  }
  capture::write_json(slurm_submission_path(sweep_dir), to_json(submission));
  return submission;
}

std::optional<SlurmSubmission> prepare_and_submit_to_slurm(const fs::path& manifest, const fs::path& sweep_dir,
                                                           const fs::path& sweep_binary, const SlurmOptions& options) {
  if (const std::optional<SlurmSubmission> earlier = read_slurm_submission(sweep_dir)) {
    for (const auto& [task, state] : slurm_task_states(*earlier)) {
      if (is_active_slurm_state(state)) {
        throw std::runtime_error(sweep_dir.string() + ": Slurm job " + earlier->job_id + " still has tasks queued or running (task " +
                                 std::to_string(task) + " is " + state + "); wait for it (avsm-sweep wait " +
                                 sweep_dir.string() + ") or cancel it (scancel " + earlier->job_id + ") before submitting again");
      }
    }
    fs::remove(slurm_submission_path(sweep_dir));  // superseded, even if sbatch refuses the new one
  }
  const SweepIndex index = prepare_sweep(manifest, sweep_dir);
  std::vector<size_t> tasks;
  for (size_t i = 0; i < index.jobs.size(); ++i) {
    JobRecord job = index.jobs[i];
    if (job.status == JobStatus::done && !options.force) continue;
    tasks.push_back(i);
    // Pending until its task starts: an earlier failure's job.json would otherwise
    // read as this submission's result. Written before sbatch, so never over a task's own.
    job.status = JobStatus::pending;
    job.exit_code.reset();
    job.error.clear();
    job.wall_s = 0.0;
    write_job_record(sweep_dir, job);
  }
  if (tasks.empty()) return std::nullopt;
  const SlurmSubmission submission = submit_to_slurm(fs::absolute(sweep_dir), sweep_binary, tasks, options);
  collect(sweep_dir);
  return submission;
}

bool is_active_slurm_state(const std::string& state) {
  static const char* const finished[] = {"COMPLETED", "FAILED", "TIMEOUT", "CANCELLED", "NODE_FAIL",
                                         "PREEMPTED", "OUT_OF_MEMORY", "BOOT_FAIL", "DEADLINE"};
  return std::none_of(std::begin(finished), std::end(finished), [&](const char* s) { return state == s; });
}

std::map<size_t, std::string> slurm_task_states(const SlurmSubmission& submission) {
  std::map<size_t, std::string> states = squeue_task_states(submission.job_id);
  const bool all_listed = std::all_of(submission.tasks.begin(), submission.tasks.end(),
                                      [&](size_t task) { return states.count(task) != 0; });
  if (!all_listed) states.merge(sacct_task_states(submission.job_id));  // merge keeps squeue's entries
  return states;
}

SweepIndex collect_with_slurm(const fs::path& sweep_dir) {
  SweepIndex index = collect(sweep_dir);
  const std::optional<SlurmSubmission> submission = read_slurm_submission(sweep_dir);
  if (!submission) return index;
  const bool unfinished = std::any_of(submission->tasks.begin(), submission->tasks.end(), [&](size_t task) {
    return task >= index.jobs.size() || !is_finished(index.jobs[task].status);
  });
  if (!unfinished) return index;  // every job has its result: no need to ask Slurm
  const std::map<size_t, std::string> states = slurm_task_states(*submission);
  bool changed = false;
  for (size_t task : submission->tasks) {
    if (task >= index.jobs.size()) {
      throw std::runtime_error(slurm_submission_path(sweep_dir).string() + ": task " + std::to_string(task) +
                               " is past the sweep's " + std::to_string(index.jobs.size()) + " jobs in index.json");
    }
    JobRecord& job = index.jobs[task];
    if (is_finished(job.status)) continue;  // its own final job.json
    const auto state = states.find(task);
    if (state != states.end() && is_active_slurm_state(state->second)) continue;  // queued or running
    // Slurm is done with the task, but the task never wrote a final job.json.
    const std::string slurm_state = state == states.end() ? "no longer listed by Slurm" : state->second;
    job.status = JobStatus::failed;
    job.error = "Slurm array task " + submission->job_id + "_" + std::to_string(task) + " ended (" + slurm_state +
                ") before the job finished; see " + slurm_task_log_path(sweep_dir, task).string();
    write_job_record(sweep_dir, job);
    changed = true;
  }
  if (changed) index = collect(sweep_dir);
  return index;
}

SweepIndex wait_for_slurm(const fs::path& sweep_dir, std::chrono::seconds timeout) {
  const std::optional<SlurmSubmission> submission = read_slurm_submission(sweep_dir);
  if (!submission) return collect(sweep_dir);  // nothing submitted: nothing to wait for
  const auto start = std::chrono::steady_clock::now(), deadline = start + timeout;
  // Polls squeue every tenth of the time waited so far, from every second to every 30
  // seconds: a sweep is seen finished within a tenth of its time (doubling the pause
  // could overshoot by as long again), and a long one does not load the controller.
  using std::chrono::milliseconds;
  for (;;) {
    SweepIndex index = collect_with_slurm(sweep_dir);
    const bool unfinished = std::any_of(submission->tasks.begin(), submission->tasks.end(),
                                        [&](size_t task) { return !is_finished(index.jobs[task].status); });
    const auto now = std::chrono::steady_clock::now();
    const milliseconds pause =
        std::clamp(std::chrono::duration_cast<milliseconds>(now - start) / 10, milliseconds(1000), milliseconds(30000));
    if (!unfinished || now + pause > deadline) return index;
    std::this_thread::sleep_for(pause);
  }
}

}  // namespace avsm::sweep
