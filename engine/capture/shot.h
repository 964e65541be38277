#pragma once
// A shot: avsm-capture --frame-range A:B renders frames A to B of the scene's animation at
// --fps, one instant each (content/README.md, "Animation"), writes each frame's image as
// frames/frame_<NNNN>.png and this report as shot.json. The first frame is kept apart
// from the figures: it pays for what the later ones reuse (pipelines, pages, buffers).
#include <nlohmann/json.hpp>

#include <cstdint>
#include <filesystem>
#include <optional>
#include <string>
#include <vector>

namespace avsm::capture {

struct FrameRange {
  int first = 0, last = 0;  // inclusive shot frame numbers
  float fps = 24.0f;
  float time_of(int frame) const { return float(frame) / fps; }
  bool operator==(const FrameRange&) const = default;
};

// "A:B" with 0 <= A <= B (or "A" alone: one frame); nullopt-like failure as false.
bool parse_frame_range(const std::string& text, FrameRange& range);

// The process's memory: resident (VmRSS) and the heap in use (glibc's mallinfo2), which
// resident memory hides while freed heap pages take the growth (as bench/soak measures).
struct ProcessMemory {
  double resident_mib = 0.0, heap_mib = 0.0;
};
ProcessMemory process_memory();

struct ShotFrame {
  int frame = 0;
  float time = 0.0f;     // seconds
  double wall_ms = 0.0;  // posing, uploading what moved, rendering (and again while maps were unfinished)
  uint32_t renders = 1;  // 1, or more where maps were unfinished
  double volume_wait_ms = 0.0;  // of wall_ms, waiting for volume sequence frames not read yet
  ProcessMemory memory;         // after the frame (a flat line over a loop: nothing leaks)
  std::filesystem::path image;
};

struct ShotSummary {
  std::size_t frames = 0;
  double first_ms = 0.0;
  // Over the frames after the first (the first's alone for a one-frame shot).
  double mean_ms = 0.0, median_ms = 0.0, max_ms = 0.0;
  int slowest_frame = 0;
};

struct ShotReport {
  FrameRange range;
  std::vector<ShotFrame> frames;
  std::filesystem::path video;  // shot.mp4 (relative to the folder); empty when none was written
  std::string video_note;       // why not, when not
  // The volume sequences' reader (renderer/volume_sequence_player.h), when the scene has any:
  // frames it read and prepared, their mean ms on its thread, and the frames that waited for it.
  struct SequenceReading {
    uint64_t frames_read = 0, waits = 0;
    double mean_read_ms = 0.0;
  };
  std::optional<SequenceReading> sequence_reading;

  ShotSummary summary() const;
  // frames/frame_<NNNN>.png, the numbering of the shot's frames (4 digits, more if needed).
  static std::filesystem::path image_name(int frame);
};

nlohmann::json to_json(const ShotReport& shot);

// shot.mp4 from the shot's frames through Debian's ffmpeg (H.264, yuv420p, at the shot's
// rate) when ffmpeg is on PATH; otherwise, or when it fails, shot.video stays empty and
// shot.video_note says why.
void write_shot_video(const std::filesystem::path& out_dir, ShotReport& shot);

}  // namespace avsm::capture
