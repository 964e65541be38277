#pragma once
// The regression gate's thresholds (avsm-compare --thresholds FILE): defaults with
// room for a GPU's run-to-run spread of timings, overridable per key from a JSON file.
// The file's format and the reasons for each default: docs/farm.md, "Regression gate".
#include <cstdint>
#include <filesystem>
#include <nlohmann/json_fwd.hpp>

namespace avsm::sweep {

struct TimingThresholds {
  // NEW / BASE of a pass's median GPU ms above this fails...
  double max_pass_ratio = 1.5;
  // ...when the pass is big enough to measure: on either side at least this many ms
  // and this share of the longer frame's GPU time. Smaller passes are listed, not judged.
  double min_pass_ms = 0.5;
  double min_pass_share = 0.05;
  // NEW / BASE of the frame's median GPU ms above this fails.
  double max_frame_ratio = 1.5;
  // Whether to judge the times of a CPU device (lavapipe) at all: on a machine whose
  // cores other work shares, an unchanged frame's pass times move by several times.
  bool judge_cpu_devices = false;
  bool operator==(const TimingThresholds&) const = default;
};

struct ImageThresholds {
  // frame.exr, RGB mapped by x / (1 + x) into [0, 1) (compare.h, image_difference)
  double min_psnr_db = 40.0;
  double max_mean_abs_error = 0.005;
  bool operator==(const ImageThresholds&) const = default;
};

struct QualityThresholds {
  // quality.json, per light: NEW mean |T - T_ref| minus BASE's above this fails.
  double max_mean_abs_error_increase = 0.002;
  bool operator==(const QualityThresholds&) const = default;
};

struct MemoryThresholds {
  // memory.json: NEW / BASE of a byte count above this fails, when the increase is
  // at least min_increase_bytes (small buffers may grow by a page without meaning).
  double max_ratio = 1.1;
  uint64_t min_increase_bytes = 65536;
  bool operator==(const MemoryThresholds&) const = default;
};

struct Thresholds {
  TimingThresholds timing;
  ImageThresholds image;
  QualityThresholds quality;
  MemoryThresholds memory;
  bool operator==(const Thresholds&) const = default;
};

// The defaults with the keys `in` sets replaced: {"timing": {"max_pass_ratio": 1.5}, ...}.
// Strict: an unknown section or key, a value of the wrong type or out of range throws
// std::runtime_error naming the key ("timing.max_pass_ratio").
Thresholds thresholds_from_json(const nlohmann::json& in);
// Every key with its value: what --thresholds accepts, and what the summary prints.
nlohmann::json to_json(const Thresholds& thresholds);
// thresholds_from_json of the file; errors are prefixed with the file's path.
Thresholds read_thresholds(const std::filesystem::path& path);

}  // namespace avsm::sweep
