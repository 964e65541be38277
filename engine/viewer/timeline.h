#pragma once
// The viewer's clock over the scene's animation: play and pause, scrub, loop, and a frame
// rate whose frames the shown time snaps to (the instants avsm-capture --fps renders).
#include <cstdint>

namespace avsm::viewer {

class Timeline {
 public:
  void set_duration(float seconds);  // the animation's (SceneAnimation::duration()); 0: nothing moves
  float duration() const { return duration_; }
  bool animated() const { return duration_ > 0.0f; }

  // The shown time: the playhead snapped down to its frame.
  float time() const;
  int frame() const;
  float fps() const { return fps_; }
  void set_fps(float fps);  // 1 to 240

  bool playing() const { return playing_; }
  void play();   // from the start when stopped at the end without looping
  void pause() { playing_ = false; }
  bool loop() const { return loop_; }
  void set_loop(bool loop) { loop_ = loop; }

  // Moves the playhead to `seconds` (clamped to the animation).
  void scrub(float seconds);
  // Advances the playhead by `seconds` of playback while playing: past the end it wraps
  // round when looping, else stops there. Returns whether the shown time changed.
  bool advance(double seconds);

 private:
  float duration_ = 0.0f;
  double playhead_ = 0.0;
  float fps_ = 24.0f;
  bool playing_ = false;
  bool loop_ = true;
};

}  // namespace avsm::viewer
