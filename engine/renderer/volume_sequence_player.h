#pragma once
// Plays a scene's volume sequences (scene/volume_sequence.h): for a time, each sequence's
// frame, prepared for the GPU (passes/frame/volume_data.h), to hand to
// SceneRenderer::show_volume_frame.
//
// Frames are read, converted to NanoVDB with their majorants, and prepared (sky lighting,
// atlas bricks) on one worker thread, ahead of the frame that shows them: asking for
// frame n queues n and the `read_ahead` frames after it in playing order. The cache holds
// at most `cache_frames` prepared frames per sequence; the ones furthest from the frame
// shown go first. Nothing here touches the device, so the frame's thread never waits for
// a read unless it asks to (a capture must show the frame of its time; the viewer keeps
// showing the last frame it had).
#include <condition_variable>
#include <cstdint>
#include <deque>
#include <map>
#include <memory>
#include <mutex>
#include <optional>
#include <string>
#include <thread>
#include <vector>

#include "passes/frame/volume_data.h"
#include "scene/load_error.h"
#include "scene/volume_sequence.h"

namespace avsm::renderer {

struct SequencePlayerOptions {
  uint32_t read_ahead = 4;    // frames prepared ahead of the one asked for
  uint32_t cache_frames = 8;  // prepared frames kept per sequence (at least read_ahead + 2)
};

class VolumeSequencePlayer {
 public:
  // `max_3d_texels`: the device's 3D image limit (the atlas regions are laid out by it).
  VolumeSequencePlayer(std::vector<scene::VolumeSequence> sequences, uint32_t max_3d_texels,
                       SequencePlayerOptions options = {});
  ~VolumeSequencePlayer();  // stops the worker (a read under way finishes first)
  VolumeSequencePlayer(const VolumeSequencePlayer&) = delete;
  VolumeSequencePlayer& operator=(const VolumeSequencePlayer&) = delete;

  struct Shown {
    uint32_t volume = 0;  // Scene::volumes index
    int frame = 0;        // file frame
    std::shared_ptr<const passes::PreparedVolume> part;
  };
  // The frames to show at `time` that differ from the ones last returned. With `wait`,
  // waits for each and throws scene::LoadError for a frame that cannot be read (naming
  // its file and frame number). Without, returns only the ones ready, and a frame that
  // failed is left out and its error kept (take_errors()): the volume keeps its last frame.
  std::vector<Shown> at(float time, bool wait);

  // Frames that could not be read since the last call (each names its file and frame).
  std::vector<scene::LoadError> take_errors();

  struct Stats {
    uint64_t frames_read = 0;   // read and prepared by the worker
    uint64_t waits = 0;         // at(wait) calls that had to wait for the worker
    double read_ms = 0.0;       // the worker's time, all frames
    std::size_t cached_frames = 0;
    std::size_t cached_bytes = 0;  // NanoVDB, sky and atlas bytes held
  };
  Stats stats() const;
  bool empty() const { return sequences_.empty(); }

 private:
  struct Entry {
    std::shared_ptr<const passes::PreparedVolume> part;  // when read
    std::optional<scene::LoadError> error;               // when it failed
    bool queued = false;
  };
  struct Sequence {
    scene::VolumeSequence description;
    std::map<int, Entry> frames;  // by file frame
    std::optional<int> shown;     // the frame last handed out
    int wanted = 0;               // the frame last asked for: the cache keeps what is near it
  };

  void request(std::size_t sequence, int frame);  // under the lock
  void evict(Sequence& sequence);                  // under the lock
  int distance(const Sequence& sequence, int frame) const;  // playing order, from the wanted frame
  void work();

  SequencePlayerOptions options_;
  uint32_t max_3d_texels_;
  mutable std::mutex mutex_;
  std::condition_variable work_ready_, frame_ready_;
  std::vector<Sequence> sequences_;
  std::deque<std::pair<std::size_t, int>> queue_;  // (sequence, frame) to read, in order
  std::vector<scene::LoadError> errors_;
  Stats stats_;
  bool stopping_ = false;
  std::thread worker_;
};

}  // namespace avsm::renderer
