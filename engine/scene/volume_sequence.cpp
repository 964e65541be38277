#include "scene/volume_sequence.h"

#include "scene/load_error.h"

#include <algorithm>
#include <set>

namespace avsm::scene {
namespace {

VolumeOptions options_of(const VolumeEntry& entry) {
  VolumeOptions options;
  options.grid_name = entry.grid;
  options.transform = entry.transform;
  options.extinction_scale = entry.extinction_scale;
  options.albedo = entry.albedo;
  options.majorant_brick_size = entry.majorant_brick_size;
  return options;
}

// The frames of `pattern` on disk.
std::set<int> frames_on_disk(const FramePattern& pattern) {
  std::set<int> frames;
  std::error_code error;
  const std::filesystem::path directory = pattern.directory.empty() ? "." : pattern.directory;
  for (const auto& file : std::filesystem::directory_iterator(directory, error))
    if (const std::optional<int> frame = pattern.frame_of(file.path().filename().string())) frames.insert(*frame);
  return frames;
}

std::string frame_label(int frame, const FramePattern& pattern) {
  return "frame " + std::to_string(frame) + " of the sequence '" + pattern.written + "'";
}

}  // namespace

Volume load_volume(const VolumeEntry& entry, const std::filesystem::path& file) {
  Volume volume = load_vdb_volume(file, options_of(entry));
  volume.name = entry.name;
  volume.lighting_cache_downsample = entry.lighting_cache_downsample;
  volume.lighting_cache = entry.lighting_cache;
  volume.multiple_scattering = entry.multiple_scattering;
  volume.sky_light = entry.sky_light;
  return volume;
}

Volume VolumeSequence::load_frame(int frame) const {
  const std::filesystem::path file = pattern.file(frame);
  try {
    return load_volume(entry, file);
  } catch (const LoadError& error) {
    throw LoadError(error.file(), frame_label(frame, pattern) + ": " + error.problem());
  }
}

VolumeSequence open_volume_sequence(const VolumeEntry& entry, const FramePattern& pattern, std::size_t volume) {
  VolumeSequence sequence;
  sequence.volume = volume;
  sequence.pattern = pattern;
  sequence.entry = entry;
  SequenceTiming& timing = sequence.timing;
  timing.fps = entry.sequence.fps;
  timing.loop = entry.sequence.loop;
  if (entry.sequence.first) {
    timing.first = *entry.sequence.first;
    timing.last = *entry.sequence.last;
  } else {
    const std::set<int> frames = frames_on_disk(pattern);
    if (frames.empty())
      throw LoadError(pattern.file(0).parent_path() / pattern.written,
                      "no file of this sequence is there (its frames would be named like '" +
                          pattern.file(1).filename().string() + "')");
    timing.first = *frames.begin();
    timing.last = *frames.rbegin();
  }
  timing.offset = entry.sequence.offset.value_or(timing.first);
  const VolumeOptions options = options_of(entry);
  for (int frame = timing.first; frame <= timing.last; ++frame) {
    const std::filesystem::path file = pattern.file(frame);
    std::error_code error;
    if (!std::filesystem::is_regular_file(file, error))
      throw LoadError(file, frame_label(frame, pattern) + " is missing (frames " + std::to_string(timing.first) +
                                " to " + std::to_string(timing.last) + " are expected; set \"sequence\": {\"frames\": [first, last]} "
                                "to the frames there are)");
    try {
      sequence.bounds.extend(read_vdb_bounds(file, options));
    } catch (const LoadError& problem) {
      throw LoadError(problem.file(), frame_label(frame, pattern) + ": " + problem.problem());
    }
  }
  return sequence;
}

}  // namespace avsm::scene
