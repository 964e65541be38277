#include "renderer/volume_sequence_player.h"

#include <algorithm>
#include <chrono>
#include <limits>
#include <stdexcept>

namespace avsm::renderer {
namespace {

std::size_t bytes_of(const passes::PreparedVolume& part) {
  return part.volume->nanovdb.size() + part.volume->majorant.max_density.size() * sizeof(float) +
         part.sky.size() * sizeof(float) + part.atlas.texels.size() * sizeof(uint16_t);
}

}  // namespace

VolumeSequencePlayer::VolumeSequencePlayer(std::vector<scene::VolumeSequence> sequences, uint32_t max_3d_texels,
                                           SequencePlayerOptions options)
    : options_(options), max_3d_texels_(max_3d_texels) {
  options_.cache_frames = std::max(options_.cache_frames, options_.read_ahead + 2);
  for (scene::VolumeSequence& description : sequences) sequences_.push_back({std::move(description), {}, {}, 0});
  if (!sequences_.empty()) worker_ = std::thread([this] { work(); });
}

VolumeSequencePlayer::~VolumeSequencePlayer() {
  {
    std::lock_guard lock(mutex_);
    stopping_ = true;
  }
  work_ready_.notify_all();
  if (worker_.joinable()) worker_.join();
}

int VolumeSequencePlayer::distance(const Sequence& sequence, int frame) const {
  const scene::SequenceTiming& timing = sequence.description.timing;
  int ahead = frame - sequence.wanted;
  if (timing.loop) ahead = ((ahead % timing.count()) + timing.count()) % timing.count();
  // Frames already played come last: a shot rarely goes back.
  return ahead >= 0 ? ahead : timing.count() - ahead;
}

void VolumeSequencePlayer::request(std::size_t sequence, int frame) {
  auto [entry, added] = sequences_[sequence].frames.try_emplace(frame);
  if (!added) return;
  entry->second.queued = true;
  queue_.emplace_back(sequence, frame);
}

void VolumeSequencePlayer::evict(Sequence& sequence) {
  while (sequence.frames.size() > options_.cache_frames) {
    auto furthest = std::max_element(sequence.frames.begin(), sequence.frames.end(), [&](const auto& a, const auto& b) {
      return distance(sequence, a.first) < distance(sequence, b.first);
    });
    sequence.frames.erase(furthest);  // a read under way for it is dropped when it ends
  }
}

std::vector<VolumeSequencePlayer::Shown> VolumeSequencePlayer::at(float time, bool wait) {
  std::unique_lock lock(mutex_);
  for (std::size_t s = 0; s < sequences_.size(); ++s) {
    Sequence& sequence = sequences_[s];
    const scene::SequenceTiming& timing = sequence.description.timing;
    sequence.wanted = timing.frame_at(time);
    request(s, sequence.wanted);
    for (uint32_t k = 1; k <= options_.read_ahead; ++k) {
      const int next = timing.loop ? timing.first + (sequence.wanted - timing.first + int(k)) % timing.count()
                                   : sequence.wanted + int(k);
      if (next <= timing.last) request(s, next);
    }
    evict(sequence);
  }
  work_ready_.notify_one();

  std::vector<Shown> shown;
  for (std::size_t s = 0; s < sequences_.size(); ++s) {
    Sequence& sequence = sequences_[s];
    const int frame = sequence.wanted;
    if (sequence.shown == frame) continue;
    const auto ready = [&] {
      const auto it = sequence.frames.find(frame);
      return it == sequence.frames.end() || !it->second.queued;
    };
    if (wait && !ready()) {
      ++stats_.waits;
      frame_ready_.wait(lock, ready);
    }
    const auto it = sequence.frames.find(frame);
    if (it == sequence.frames.end() || it->second.queued) continue;
    if (it->second.part) {
      shown.push_back({uint32_t(sequence.description.volume), frame, it->second.part});
      sequence.shown = frame;
    } else if (wait) {
      throw *it->second.error;
    } else {
      errors_.push_back(*it->second.error);
      sequence.shown = frame;  // said once; the volume keeps its last good frame
    }
  }
  return shown;
}

std::vector<scene::LoadError> VolumeSequencePlayer::take_errors() {
  std::lock_guard lock(mutex_);
  return std::exchange(errors_, {});
}

VolumeSequencePlayer::Stats VolumeSequencePlayer::stats() const {
  std::lock_guard lock(mutex_);
  Stats stats = stats_;
  for (const Sequence& sequence : sequences_)
    for (const auto& [frame, entry] : sequence.frames)
      if (entry.part) {
        ++stats.cached_frames;
        stats.cached_bytes += bytes_of(*entry.part);
      }
  return stats;
}

void VolumeSequencePlayer::work() {
  std::unique_lock lock(mutex_);
  for (;;) {
    work_ready_.wait(lock, [&] { return stopping_ || !queue_.empty(); });
    if (stopping_) return;
    // The queued frame nearest to what its sequence shows next.
    const auto next = std::min_element(queue_.begin(), queue_.end(), [&](const auto& a, const auto& b) {
      return distance(sequences_[a.first], a.second) < distance(sequences_[b.first], b.second);
    });
    const auto [s, frame] = *next;
    queue_.erase(next);
    if (!sequences_[s].frames.count(frame)) continue;  // evicted before its turn
    const scene::VolumeSequence& description = sequences_[s].description;  // never changes
    lock.unlock();

    const auto start = std::chrono::steady_clock::now();
    std::shared_ptr<const passes::PreparedVolume> part;
    std::optional<scene::LoadError> error;
    try {
      auto volume = std::make_shared<scene::Volume>(description.load_frame(frame));
      part = std::make_shared<passes::PreparedVolume>(passes::prepare_volume(std::move(volume), description.volume, max_3d_texels_));
    } catch (const scene::LoadError& problem) {
      error = problem;
    } catch (const std::exception& problem) {  // what the GPU could not take (prepare_volume)
      error = scene::LoadError(description.pattern.file(frame),
                               "frame " + std::to_string(frame) + " of the sequence '" + description.pattern.written + "': " + problem.what());
    }
    const double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();

    lock.lock();
    ++stats_.frames_read;
    stats_.read_ms += ms;
    const auto it = sequences_[s].frames.find(frame);
    if (it != sequences_[s].frames.end()) {
      it->second.part = std::move(part);
      it->second.error = std::move(error);
      it->second.queued = false;
    }
    frame_ready_.notify_all();
  }
}

}  // namespace avsm::renderer
