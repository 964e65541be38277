#include "capture/shot.h"

#include "capture/run_command.h"

#include <algorithm>
#include <charconv>
#include <cstdio>
#include <fstream>
#include <malloc.h>
#include <numeric>

namespace avsm::capture {
namespace {

bool parse_int(std::string_view text, int& value) {
  const auto [end, error] = std::from_chars(text.data(), text.data() + text.size(), value);
  return error == std::errc() && end == text.data() + text.size();
}

}  // namespace

ProcessMemory process_memory() {
  ProcessMemory memory;
  std::ifstream status("/proc/self/status");
  for (std::string line; std::getline(status, line);)
    if (line.rfind("VmRSS:", 0) == 0) memory.resident_mib = std::stod(line.substr(6)) / 1024.0;  // "VmRSS:  1234 kB"
  memory.heap_mib = double(mallinfo2().uordblks) / (1024.0 * 1024.0);
  return memory;
}

bool parse_frame_range(const std::string& text, FrameRange& range) {
  const std::size_t colon = text.find(':');
  const std::string_view whole(text);
  int first = 0, last = 0;
  if (colon == std::string::npos) {
    if (!parse_int(whole, first)) return false;
    last = first;
  } else if (!parse_int(whole.substr(0, colon), first) || !parse_int(whole.substr(colon + 1), last)) {
    return false;
  }
  if (first < 0 || last < first) return false;
  range.first = first;
  range.last = last;
  return true;
}

std::filesystem::path ShotReport::image_name(int frame) {
  char name[32];
  std::snprintf(name, sizeof name, "frame_%04d.png", frame);
  return std::filesystem::path("frames") / name;
}

ShotSummary ShotReport::summary() const {
  ShotSummary summary;
  summary.frames = frames.size();
  if (frames.empty()) return summary;
  summary.first_ms = frames.front().wall_ms;
  const std::size_t skip = frames.size() > 1 ? 1 : 0;
  std::vector<double> walls;
  for (std::size_t i = skip; i < frames.size(); ++i) walls.push_back(frames[i].wall_ms);
  summary.mean_ms = std::accumulate(walls.begin(), walls.end(), 0.0) / double(walls.size());
  std::vector<double> sorted = walls;
  std::sort(sorted.begin(), sorted.end());
  summary.median_ms = sorted.size() % 2 ? sorted[sorted.size() / 2]
                                        : 0.5 * (sorted[sorted.size() / 2 - 1] + sorted[sorted.size() / 2]);
  const auto slowest = std::max_element(frames.begin() + std::ptrdiff_t(skip), frames.end(),
                                        [](const ShotFrame& a, const ShotFrame& b) { return a.wall_ms < b.wall_ms; });
  summary.max_ms = slowest->wall_ms;
  summary.slowest_frame = slowest->frame;
  return summary;
}

void write_shot_video(const std::filesystem::path& out_dir, ShotReport& shot) {
  if (shot.frames.empty()) return;
  char rate[32];
  std::snprintf(rate, sizeof rate, "%g", double(shot.range.fps));
  // Even sizes: yuv420p halves the chroma planes.
  const std::optional<CommandResult> result = run_command(
      {"ffmpeg", "-y", "-loglevel", "error", "-framerate", rate, "-start_number", std::to_string(shot.range.first), "-i",
       (out_dir / "frames" / "frame_%04d.png").string(), "-vf", "scale=trunc(iw/2)*2:trunc(ih/2)*2", "-c:v", "libx264",
       "-pix_fmt", "yuv420p", (out_dir / "shot.mp4").string()});
  if (!result) {
    shot.video_note = "ffmpeg is not installed, so no shot.mp4 (Debian: apt install ffmpeg)";
  } else if (result->exit_code != 0) {
    shot.video_note = "ffmpeg failed (exit status " + std::to_string(result->exit_code) + "): " + result->err;
  } else {
    shot.video = "shot.mp4";
  }
}

nlohmann::json to_json(const ShotReport& shot) {
  nlohmann::json frames = nlohmann::json::array();
  for (const ShotFrame& f : shot.frames)
    frames.push_back({{"frame", f.frame}, {"time", f.time}, {"wall_ms", f.wall_ms}, {"renders", f.renders},
                      {"volume_wait_ms", f.volume_wait_ms}, {"resident_mib", f.memory.resident_mib},
                      {"heap_mib", f.memory.heap_mib}, {"image", f.image.generic_string()}});
  const ShotSummary s = shot.summary();
  nlohmann::json video = shot.video.empty() ? nlohmann::json(nullptr) : nlohmann::json(shot.video.generic_string());
  nlohmann::json reading = nullptr;
  if (shot.sequence_reading)
    reading = {{"frames_read", shot.sequence_reading->frames_read},
               {"mean_read_ms", shot.sequence_reading->mean_read_ms},
               {"frames_that_waited", shot.sequence_reading->waits}};
  return {{"video", video},
          {"volume_sequence_reading", reading},
          {"video_note", shot.video_note},
          {"first_frame", shot.range.first},
          {"last_frame", shot.range.last},
          {"fps", shot.range.fps},
          {"frames", frames},
          {"summary",
           {{"frames", s.frames}, {"first_ms", s.first_ms}, {"mean_ms_after_first", s.mean_ms},
            {"median_ms_after_first", s.median_ms}, {"max_ms_after_first", s.max_ms}, {"slowest_frame", s.slowest_frame}}}};
}

}  // namespace avsm::capture
