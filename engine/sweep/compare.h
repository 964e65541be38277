#pragma once
// The regression gate (avsm-compare BASE NEW): two capture folders, or two sweep
// folders job by job, compared check by check against Thresholds. Every figure is
// read back through the typed reports (capture/frame_report.h, sweep/sweep_index.h)
// and frame.exr through io/image_io.h.
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

#include "capture/frame_report.h"
#include "gpu/transfer.h"
#include "sweep/gate_thresholds.h"

namespace avsm::sweep {

enum class Verdict {
  pass,
  fail,    // a threshold crossed, or NEW lacks what BASE had (a failed job, a different image size),
           // or the two sides were captured with different settings
  listed,  // reported but not judged: a pass too small to time, a pass or light on one side only
};

// How the gate judges, apart from its thresholds (avsm-compare's flags).
struct CompareOptions {
  // --allow-different-settings: settings that differ between BASE and NEW are listed
  // rather than failed (to measure on purpose what a change of settings costs).
  bool allow_different_settings = false;
};

struct Check {
  std::string name;          // "gpu_ms 'light 0 capture opaque'", "image psnr", "memory 'sun' map_bytes"
  std::string base, now;     // the figures as shown; "-" where a side has none
  std::string change;        // "x1.25", "-3.1 dB", "+0.0012"
  std::string limit;         // the threshold as shown: "x2.00", ">= 40 dB"
  Verdict verdict = Verdict::pass;
  std::string message;       // why it failed or was only listed; empty when it passed
};

// One job of a sweep, or the one pair of captures.
struct SuiteResult {
  std::string name;  // the job id, or "capture"
  std::vector<Check> checks;
  size_t failures() const;
};

struct GateResult {
  std::string base, now;  // the folders
  std::vector<SuiteResult> suites;
  size_t failures() const;
};

// ---- the checks, one figure kind at a time (on reports already read) ----

// The settings two captures were made with, key by key: one check per setting that differs
// ("setting 'light sun' nodes", "setting width"), failed unless options allow it (then
// listed); one passing "settings" check when none differs. When a side has no
// settings.json (captured before it was written), only what both sides' timings.json and
// memory.json record is compared (the image size; per light its technique, nodes, map
// resolution, map kind and build), with a listed "settings.json" check saying which side lacks it.
std::vector<Check> compare_settings(const capture::FrameReport& base, const capture::FrameReport& now,
                                    const CompareOptions& options);

std::vector<Check> compare_timings(const capture::TimingReport& base, const capture::TimingReport& now,
                                   const TimingThresholds& limits);
// Per light of quality.json, matched by name; no checks when either side has no quality.json.
std::vector<Check> compare_quality(const std::optional<capture::QualityReport>& base,
                                   const std::optional<capture::QualityReport>& now,
                                   const QualityThresholds& limits);
// Per light (map_bytes, capture_bytes, matched by name) and the frame's transient_bytes_aliased.
std::vector<Check> compare_memory(const capture::MemoryReport& base, const capture::MemoryReport& now,
                                  const MemoryThresholds& limits);

// PSNR and mean absolute error; one failing check when the sizes differ.
std::vector<Check> compare_images(const gpu::ImageRGBA32F& base, const gpu::ImageRGBA32F& now,
                                  const ImageThresholds& limits);

// Two shots (avsm-capture --frame-range: shot.json and frames/), frame by frame: each
// frame both have compared as compare_images() does, and the worst frame reported: "shot
// worst psnr" and "shot worst mean_abs_error" name it and are judged against the image
// thresholds; "shot frames" fails when NEW lacks frames BASE has (and lists frames only NEW
// has). No checks when neither folder holds a shot; one failing check when only one does.
// Throws std::runtime_error naming a shot.json or frame image that is missing or malformed.
std::vector<Check> compare_shots(const std::filesystem::path& base, const std::filesystem::path& now,
                                 const ImageThresholds& limits);

// ---- folders ----

// Every check of two capture folders (avsm-capture --out): settings.json (first),
// timings.json, memory.json, quality.json (when both have one), frame.exr, and the shot's
// frames (compare_shots) when they hold shots. Throws
// std::runtime_error naming the file that is missing or malformed.
SuiteResult compare_captures(const std::string& name, const std::filesystem::path& base,
                             const std::filesystem::path& now, const Thresholds& limits,
                             const CompareOptions& options = {});

// Two capture folders, or two sweep folders (with index.json; jobs matched by id, each
// done pair compared as captures). Throws std::runtime_error when a folder is neither,
// or the two are not of the same kind, or a file is missing or malformed.
GateResult compare_folders(const std::filesystem::path& base, const std::filesystem::path& now,
                           const Thresholds& limits, const CompareOptions& options = {});

// ---- output ----

// A table per suite and a last line: "PASS: ..." or "FAIL: N checks crossed ...".
std::string summary_text(const GateResult& result);
// JUnit XML: one <testsuite> per suite, one <testcase> per check; <failure> for a failed
// check, <skipped> for a listed one.
std::string junit_xml(const GateResult& result);

}  // namespace avsm::sweep
