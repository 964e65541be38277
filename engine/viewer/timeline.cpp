#include "viewer/timeline.h"

#include <algorithm>
#include <cmath>

namespace avsm::viewer {

void Timeline::set_duration(float seconds) {
  duration_ = std::max(0.0f, seconds);
  playhead_ = std::clamp(playhead_, 0.0, double(duration_));
  if (!animated()) playing_ = false;
}

float Timeline::time() const { return float(frame()) / fps_; }

// The frame the playhead is in; a hair's breadth below a frame's instant counts as that
// frame (playheads summed from steps of 1 / fps fall just short of it).
int Timeline::frame() const { return int(std::floor(playhead_ * fps_ + 1e-4)); }

void Timeline::set_fps(float fps) { fps_ = std::clamp(fps, 1.0f, 240.0f); }

void Timeline::play() {
  if (!animated()) return;
  if (!loop_ && playhead_ >= duration_) playhead_ = 0.0;
  playing_ = true;
}

void Timeline::scrub(float seconds) { playhead_ = std::clamp(double(seconds), 0.0, double(duration_)); }

bool Timeline::advance(double seconds) {
  if (!playing_ || !animated()) return false;
  const int before = frame();
  playhead_ += std::max(0.0, seconds);
  if (playhead_ > duration_) {
    if (loop_) {
      playhead_ = std::fmod(playhead_, double(duration_));
    } else {
      playhead_ = duration_;
      playing_ = false;
    }
  }
  return frame() != before;
}

}  // namespace avsm::viewer
