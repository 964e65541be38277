#pragma once
// Headless frame capture: render K frames offscreen, write the last one as PNG
// and EXR, and the per-pass GPU timings as JSON. What avsm-capture runs.
#include <cstdint>
#include <filesystem>
#include <string>

namespace avsm::capture {

struct CaptureOptions {
  std::filesystem::path out_dir = "out/capture";
  uint32_t width = 1280;
  uint32_t height = 720;
  uint32_t frames = 5;  // timing statistics over frames after the first (warm-up)
  bool validation = false;
  std::string device;  // see gpu::ContextDesc::device
  bool progress = true;  // progress lines on stderr
};

struct CaptureOutputs {
  std::filesystem::path png;
  std::filesystem::path exr;
  std::filesystem::path timings;
};

// Throws std::runtime_error with a message for the user on any failure.
CaptureOutputs run_capture(const CaptureOptions& options);

}  // namespace avsm::capture
