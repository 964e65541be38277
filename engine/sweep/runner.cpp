#include "sweep/runner.h"

#include <fcntl.h>
#include <spawn.h>
#include <sys/wait.h>
#include <unistd.h>

#include <algorithm>
#include <atomic>
#include <cerrno>
#include <chrono>
#include <cstdlib>
#include <cstring>
#include <fstream>
#include <mutex>
#include <stdexcept>
#include <thread>

#include "sweep/manifest.h"

extern char** environ;

namespace avsm::sweep {
namespace fs = std::filesystem;

namespace {

constexpr size_t kErrorLines = 3;  // of a log without the capture's own error line

// The capture's own error ("avsm-capture: ..." that is not a warning), else the last
// lines of the log (a crash, a message from a library).
std::string error_from_log(const fs::path& log) {
  std::ifstream in(log);
  std::vector<std::string> lines;
  std::string capture_error;
  for (std::string line; std::getline(in, line);) {
    if (line.empty()) continue;
    if (line.rfind("avsm-capture: ", 0) == 0 && line.rfind("avsm-capture: warning", 0) != 0) capture_error = line;
    lines.push_back(line);
  }
  if (!capture_error.empty()) return capture_error;
  std::string tail;
  for (size_t i = lines.size() > kErrorLines ? lines.size() - kErrorLines : 0; i < lines.size(); ++i)
    tail += (tail.empty() ? "" : "\n") + lines[i];
  return tail;
}

struct ChildResult {
  int exit_code = 0;
  std::string error;  // set when the child could not run or was killed
};

// Runs `program args...` with stdout and stderr to `log` and waits for it.
ChildResult run_child(const fs::path& program, const std::vector<std::string>& args, const fs::path& log) {
  posix_spawn_file_actions_t files;
  posix_spawn_file_actions_init(&files);
  posix_spawn_file_actions_addopen(&files, STDIN_FILENO, "/dev/null", O_RDONLY, 0);
  posix_spawn_file_actions_addopen(&files, STDOUT_FILENO, log.c_str(), O_WRONLY | O_CREAT | O_TRUNC, 0644);
  posix_spawn_file_actions_adddup2(&files, STDOUT_FILENO, STDERR_FILENO);
  std::vector<std::string> argv_strings = {program.string()};
  argv_strings.insert(argv_strings.end(), args.begin(), args.end());
  std::vector<char*> argv;
  for (std::string& arg : argv_strings) argv.push_back(arg.data());
  argv.push_back(nullptr);
  pid_t pid = 0;
  const int spawned = posix_spawn(&pid, program.c_str(), &files, nullptr, argv.data(), environ);
  posix_spawn_file_actions_destroy(&files);
  if (spawned != 0) return {127, "cannot run " + program.string() + ": " + std::strerror(spawned)};
  int status = 0;
  while (waitpid(pid, &status, 0) < 0 && errno == EINTR) {
  }
  if (WIFSIGNALED(status)) {
    const int signal = WTERMSIG(status);
    return {128 + signal, "avsm-capture was killed by signal " + std::to_string(signal) + " (" + strsignal(signal) + ")"};
  }
  return {WEXITSTATUS(status), ""};
}

}  // namespace

fs::path find_capture_executable() {
  fs::path capture;
  if (const char* configured = std::getenv("AVSM_CAPTURE"); configured && *configured) {
    capture = configured;
  } else {
    std::error_code ec;
    capture = fs::read_symlink("/proc/self/exe", ec).parent_path() / "avsm-capture";
  }
  if (::access(capture.c_str(), X_OK) != 0)
    throw std::runtime_error(capture.string() + ": not an executable avsm-capture (set AVSM_CAPTURE to one)");
  return capture;
}

SweepIndex prepare_sweep(const fs::path& manifest, const fs::path& sweep_dir) {
  SweepIndex index = read_manifest(manifest);
  std::error_code ec;
  fs::create_directories(sweep_dir, ec);
  if (ec) throw std::runtime_error(sweep_dir.string() + ": cannot create the sweep folder (" + ec.message() + ")");
  const fs::path copy = sweep_dir / "manifest.json";
  if (!fs::equivalent(manifest, copy, ec)) {
    fs::copy_file(manifest, copy, fs::copy_options::overwrite_existing, ec);
    if (ec) throw std::runtime_error(copy.string() + ": cannot write (" + ec.message() + ")");
  }
  for (const JobRecord& job : index.jobs) {
    const std::optional<JobRecord> earlier = read_job_record(sweep_dir, job.id);
    if (earlier && (earlier->settings != job.settings || earlier->capture_args != job.capture_args))
      fs::remove(job_file(sweep_dir, job.id));
  }
  write_index(sweep_dir, index);
  return collect(sweep_dir);
}

JobRun run_job(const fs::path& sweep_dir, size_t index, const JobRunOptions& options) {
  const SweepIndex sweep = read_index(sweep_dir);
  if (index >= sweep.jobs.size())
    throw std::runtime_error(index_file(sweep_dir).string() + ": has " + std::to_string(sweep.jobs.size()) +
                             " jobs (0 to " + std::to_string(sweep.jobs.size()) + " - 1); there is no job " +
                             std::to_string(index));
  JobRecord job = sweep.jobs[index];
  const std::optional<JobRecord> earlier = read_job_record(sweep_dir, job.id);
  if (earlier && earlier->status == JobStatus::done && !options.force && earlier->settings == job.settings &&
      earlier->capture_args == job.capture_args)
    return {*earlier, true};

  const fs::path out = fs::absolute(sweep_dir / job.output);
  std::error_code ec;
  fs::remove_all(out, ec);
  job.status = JobStatus::running;
  write_job_record(sweep_dir, job);  // creates the folder

  std::vector<std::string> args = job.capture_args;
  args.insert(args.end(), {"--out", out.string()});
  const auto start = std::chrono::steady_clock::now();
  const ChildResult result = run_child(options.capture, args, out / "log.txt");
  job.wall_s = std::chrono::duration<double>(std::chrono::steady_clock::now() - start).count();
  job.exit_code = result.exit_code;
  job.status = result.exit_code == 0 ? JobStatus::done : JobStatus::failed;
  if (job.status == JobStatus::failed)
    job.error = result.error.empty() ? error_from_log(out / "log.txt") : result.error;
  write_job_record(sweep_dir, job);
  return {job, false};
}

SweepIndex run_sweep(const fs::path& sweep_dir, const SweepRunOptions& options) {
  const size_t job_count = read_index(sweep_dir).jobs.size();
  std::atomic<size_t> next{0};
  std::mutex report;
  std::vector<std::string> errors;  // a job that could not even be recorded (its folder unwritable)
  auto worker = [&] {
    for (size_t i = next++; i < job_count; i = next++) {
      try {
        const JobRun run = run_job(sweep_dir, i, options.job);
        std::lock_guard lock(report);
        if (options.on_job_finished) options.on_job_finished(run);
      } catch (const std::exception& e) {
        std::lock_guard lock(report);
        errors.push_back(e.what());
      }
    }
  };
  std::vector<std::thread> workers;
  for (unsigned w = 0; w < std::max(1u, options.parallel_jobs); ++w) workers.emplace_back(worker);
  for (std::thread& w : workers) w.join();
  if (!errors.empty()) throw std::runtime_error(errors.front());
  return collect(sweep_dir);
}

}  // namespace avsm::sweep
