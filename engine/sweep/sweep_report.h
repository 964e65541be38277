#pragma once
// The sweep's report: one self-contained HTML page (no external resources, no script)
// over every job of a sweep folder (sweep/sweep_index.h): a table of the jobs' settings,
// status, per-stage GPU times, memory and errors; their frames side by side at one
// scale, a row per scene and a column per technique; and the error-against-cost
// scatter of the AVSM paper's trade-off. What `avsm-sweep report DIR` writes.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "capture/frame_report.h"
#include "capture/image_difference.h"
#include "capture/pass_stages.h"
#include "sweep/sweep_index.h"

namespace avsm::sweep {

// One job as the report shows it: its record and what its capture folder holds.
struct JobResult {
  JobRecord job;
  std::string technique;                      // "AVSM-8", "OSM-32", ...: the label of what it rendered
  std::optional<capture::FrameReport> frame;  // a done job whose folder read back
  std::string problem;                        // why a done job has no frame (the reader's error)
  capture::StageTimes stage_ms{};             // per capture::kPassStages (zero without a frame)
  // Against uncompressed (quality.json), all lights' receivers together.
  std::optional<capture::ErrorStats> shadow_error;
  // frame.exr against its reference job's; the reason when there is a reference job but no figure.
  std::optional<capture::ImageDifference> image_error;
  std::string image_error_problem;
};

// Every job of `index`, in its order, read from sweep_dir. Never throws for one job's
// folder: what could not be read is in that job's problem fields.
std::vector<JobResult> read_job_results(const std::filesystem::path& sweep_dir, const SweepIndex& index);

// Reads sweep_dir/index.json (throws std::runtime_error naming it when unusable) and
// every job's folder, and writes html_path.
void write_sweep_report(const std::filesystem::path& sweep_dir, const std::filesystem::path& html_path);

}  // namespace avsm::sweep
