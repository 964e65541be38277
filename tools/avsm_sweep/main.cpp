// avsm-sweep: captures over scenes x settings, from a manifest, as a folder of capture
// folders with one index (docs/farm.md).
#include <algorithm>
#include <chrono>
#include <cstdio>
#include <cstdlib>
#include <exception>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "scene/load_error.h"
#include "sweep/runner.h"
#include "sweep/slurm.h"
#include "sweep/sweep_index.h"
#include "sweep/sweep_report.h"

namespace {

using namespace avsm::sweep;
namespace fs = std::filesystem;

const char* kUsage =
    "usage:\n"
    "  avsm-sweep run MANIFEST --out DIR [--jobs N] [--force]\n"
    "                   prepare, run every job here (N at once, default 1), collect; a re-run\n"
    "                   skips the jobs already done unless --force. Exit 1 when a job failed\n"
    "  avsm-sweep prepare MANIFEST --out DIR   check the manifest, write DIR/index.json\n"
    "  avsm-sweep task DIR --index I [--force] run job I (0-based, manifest order) of a\n"
    "                   prepared sweep (what a Slurm array task runs). Exit 1 when it failed\n"
    "  avsm-sweep collect DIR                  rebuild DIR/index.json from DIR/*/job.json\n"
    "  avsm-sweep slurm MANIFEST --out DIR [--partition P] [--time T] [--mem M] [--gres G]\n"
    "                   [--sbatch-arg A]... [--force]\n"
    "                   prepare, then submit the jobs not done as one Slurm job array\n"
    "                   (DIR/slurm/sweep.sbatch); DIR must be on storage every node shares\n"
    "  avsm-sweep wait DIR [--timeout S]       until every submitted Slurm task finished (or S\n"
    "                   seconds), then status\n"
    "  avsm-sweep status DIR                   a table of the jobs; exit 0 all done, 1 some\n"
    "                   failed, 3 some not finished\n"
    "  avsm-sweep report DIR                   collect, then DIR/report.html: one page over every job\n"
    "Each job runs avsm-capture (the one next to avsm-sweep, or $AVSM_CAPTURE) into DIR/<job id>/.\n"
    "Exit 2: a bad command line, manifest or sweep folder.\n";

constexpr int kUsageExit = 2;

struct UsageError : std::runtime_error {
  using std::runtime_error::runtime_error;
};

// A subcommand's arguments: one positional (MANIFEST or DIR) and flags.
class Arguments {
 public:
  Arguments(std::vector<std::string> args, std::vector<std::string> flags_with_values, std::vector<std::string> switches) {
    for (size_t i = 0; i < args.size(); ++i) {
      const std::string& arg = args[i];
      if (contains(switches, arg)) {
        values_[arg].push_back("");
      } else if (contains(flags_with_values, arg)) {
        if (i + 1 >= args.size()) throw UsageError(arg + " needs a value");
        values_[arg].push_back(args[++i]);
      } else if (arg.rfind("--", 0) == 0 || !positional_.empty()) {
        throw UsageError("unexpected argument '" + arg + "'");
      } else {
        positional_ = arg;
      }
    }
    if (positional_.empty()) throw UsageError("missing the manifest or sweep folder");
  }
  const std::string& positional() const { return positional_; }
  bool has(const std::string& flag) const { return values_.count(flag) != 0; }
  std::string required(const std::string& flag) const {
    if (!has(flag)) throw UsageError(flag + " is required");
    return values_.at(flag).back();
  }
  // The flag's value, empty when not given; `all`: every value of a repeatable flag.
  std::string value(const std::string& flag) const { return has(flag) ? values_.at(flag).back() : ""; }
  std::vector<std::string> all(const std::string& flag) const { return has(flag) ? values_.at(flag) : std::vector<std::string>{}; }
  // A whole number >= `lo`, or `fallback` when the flag is not given.
  unsigned number(const std::string& flag, unsigned fallback, unsigned lo) const {
    if (!has(flag)) return fallback;
    const std::string& text = values_.at(flag).back();
    char* end = nullptr;
    const unsigned long n = std::strtoul(text.c_str(), &end, 10);
    if (text.empty() || *end != '\0' || text[0] == '-' || n < lo || n > 100000)
      throw UsageError(flag + " expects a whole number from " + std::to_string(lo) + ", got '" + text + "'");
    return unsigned(n);
  }

 private:
  static bool contains(const std::vector<std::string>& list, const std::string& item) {
    for (const std::string& entry : list)
      if (entry == item) return true;
    return false;
  }
  std::string positional_;
  std::map<std::string, std::vector<std::string>> values_;  // in command-line order
};

void print_job(const JobRun& run) {
  const JobRecord& job = run.record;
  if (run.skipped) {
    std::printf("%-28s skipped (done before)\n", job.id.c_str());
  } else {
    std::printf("%-28s %-7s %6.1f s%s%s\n", job.id.c_str(), std::string(to_string(job.status)).c_str(), job.wall_s,
                job.error.empty() ? "" : "  ", job.error.c_str());
  }
  std::fflush(stdout);
}

bool all_done(const SweepIndex& index) {
  for (const JobRecord& job : index.jobs)
    if (job.status != JobStatus::done) return false;
  return true;
}

int run(const std::vector<std::string>& args) {
  const Arguments a(args, {"--out", "--jobs"}, {"--force"});
  const fs::path dir = a.required("--out");
  SweepRunOptions options;
  options.parallel_jobs = a.number("--jobs", 1, 1);
  options.job = {find_capture_executable(), a.has("--force")};
  options.on_job_finished = print_job;
  const SweepIndex prepared = prepare_sweep(a.positional(), dir);
  std::printf("%zu jobs into %s, %u at once\n", prepared.jobs.size(), dir.c_str(), options.parallel_jobs);
  const SweepIndex index = run_sweep(dir, options);
  size_t failed = 0;
  for (const JobRecord& job : index.jobs) failed += job.status == JobStatus::failed;
  std::printf("%zu of %zu jobs done, %zu failed: %s\n", index.jobs.size() - failed, index.jobs.size(), failed,
              index_file(dir).c_str());
  return all_done(index) ? 0 : 1;
}

int prepare(const std::vector<std::string>& args) {
  const Arguments a(args, {"--out"}, {});
  const fs::path dir = a.required("--out");
  const SweepIndex index = prepare_sweep(a.positional(), dir);
  std::printf("%zu jobs: %s\n", index.jobs.size(), index_file(dir).c_str());
  return 0;
}

int task(const std::vector<std::string>& args) {
  const Arguments a(args, {"--index"}, {"--force"});
  a.required("--index");
  const unsigned index = a.number("--index", 0, 0);
  const JobRun run = run_job(a.positional(), index, {find_capture_executable(), a.has("--force")});
  print_job(run);
  return run.record.status == JobStatus::done ? 0 : 1;
}

int collect_command(const std::vector<std::string>& args) {
  const Arguments a(args, {}, {});
  const SweepIndex index = collect(a.positional());
  std::printf("%zu jobs: %s\n", index.jobs.size(), index_file(a.positional()).c_str());
  return 0;
}

int status(const std::vector<std::string>& args) {
  const Arguments a(args, {}, {});
  const SweepIndex index = collect_with_slurm(a.positional());  // collect() when DIR was not submitted to Slurm
  size_t id_width = 2;
  for (const JobRecord& job : index.jobs) id_width = std::max(id_width, job.id.size());
  std::printf("%-*s  %-7s  %4s  %8s  %s\n", int(id_width), "id", "status", "exit", "wall s", "error");
  bool failed = false, unfinished = false;
  for (const JobRecord& job : index.jobs) {
    const std::string exit_code = job.exit_code ? std::to_string(*job.exit_code) : "-";
    const std::string error = job.error.substr(0, job.error.find('\n'));  // the first line; index.json has all
    std::printf("%-*s  %-7s  %4s  %8.1f  %s\n", int(id_width), job.id.c_str(), std::string(to_string(job.status)).c_str(),
                exit_code.c_str(), job.wall_s, error.c_str());
    failed |= job.status == JobStatus::failed;
    unfinished |= job.status == JobStatus::pending || job.status == JobStatus::running;
  }
  return unfinished ? 3 : failed ? 1 : 0;
}

// `slurm`: prepare DIR and submit its jobs not done yet as one Slurm job array.
int slurm(const std::vector<std::string>& args) {
  const Arguments a(args, {"--out", "--partition", "--time", "--mem", "--gres", "--sbatch-arg"}, {"--force"});
  const fs::path dir = fs::absolute(a.required("--out"));
  SlurmOptions options;
  options.partition = a.value("--partition");
  options.time = a.value("--time");
  options.mem = a.value("--mem");
  options.gres = a.value("--gres");
  options.sbatch_args = a.all("--sbatch-arg");
  options.force = a.has("--force");
  find_capture_executable();  // the tasks run the avsm-capture next to this avsm-sweep: fail here, not on the nodes
  std::error_code ec;
  const fs::path self = fs::read_symlink("/proc/self/exe", ec);
  const std::optional<SlurmSubmission> submission = prepare_and_submit_to_slurm(a.positional(), dir, self, options);
  if (!submission) {
    std::printf("every job of %s is done already; nothing submitted (--force runs them again)\n", dir.c_str());
    return 0;
  }
  std::printf("Slurm job %s: %zu tasks (%s); follow with: avsm-sweep wait %s\n", submission->job_id.c_str(),
              submission->tasks.size(), submission->script.c_str(), dir.c_str());
  return 0;
}

// `wait`: until every submitted Slurm task has finished (or --timeout), then status.
int wait_command(const std::vector<std::string>& args) {
  const Arguments a(args, {"--timeout"}, {});
  wait_for_slurm(a.positional(), std::chrono::seconds(a.number("--timeout", 24 * 3600, 1)));
  return status({a.positional()});
}

int report(const std::vector<std::string>& args) {
  const Arguments a(args, {}, {});
  collect(a.positional());  // the jobs' latest job.json, as status reads them
  const fs::path html = fs::path(a.positional()) / "report.html";
  write_sweep_report(a.positional(), html);
  std::printf("%s\n", html.c_str());
  return 0;
}

}  // namespace

int main(int argc, char** argv) {
  const std::map<std::string, int (*)(const std::vector<std::string>&)> commands = {
      {"run", run}, {"prepare", prepare}, {"task", task}, {"collect", collect_command}, {"status", status},
      {"slurm", slurm}, {"wait", wait_command}, {"report", report}};
  const std::vector<std::string> args(argv + std::min(argc, 2), argv + argc);
  const std::string command = argc > 1 ? argv[1] : "";
  if (command == "--help" || command == "-h") {
    std::printf("%s", kUsage);
    return 0;
  }
  const auto found = commands.find(command);
  try {
    if (found == commands.end()) throw UsageError(command.empty() ? "missing a command" : "unknown command '" + command + "'");
    return found->second(args);
  } catch (const UsageError& e) {
    std::fprintf(stderr, "avsm-sweep: %s\n%s", e.what(), kUsage);
  } catch (const std::exception& e) {  // a bad manifest (LoadError: file and JSON path) or sweep folder
    std::fprintf(stderr, "avsm-sweep: error: %s\n", e.what());
  }
  return kUsageExit;
}
