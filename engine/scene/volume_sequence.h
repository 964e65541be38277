#pragma once
// Volume sequences: smoke simulated in Houdini, EmberGen or Blender arrives as one
// OpenVDB file per frame, named by a frame-number pattern. A scene file's volume whose
// `file` holds such a pattern plays its frames over time (content/README.md, "Volume
// sequences"); renderer/volume_sequence_player.h reads them ahead on a worker thread.
#include "scene/bounds.h"
#include "scene/frame_pattern.h"
#include "scene/description.h"
#include "scene/volume.h"

#include <filesystem>
#include <string>

namespace avsm::scene {

// One volume of the scene whose frames come from a sequence.
struct VolumeSequence {
  std::size_t volume = 0;  // Scene::volumes index (it holds the frame shown at load)
  FramePattern pattern;
  SequenceTiming timing;
  VolumeEntry entry;       // the scene file's settings, applied to every frame
  Bounds bounds;           // every frame's, together

  // Reads file frame `frame` (in first..last) with the entry's settings. Throws
  // LoadError naming the frame's file and the frame number.
  Volume load_frame(int frame) const;
};

// The settings of `entry`'s sequence, checked against the files on disk: every frame of
// the range must be there (frames not given: the range on disk, without gaps). Reads
// each frame's header for its bounds, not its voxels. Throws LoadError naming the first
// missing frame's file, or a frame whose header is broken.
VolumeSequence open_volume_sequence(const VolumeEntry& entry, const FramePattern& pattern, std::size_t volume);

// A volume file read with a scene file entry's settings (grid, placement, optics).
Volume load_volume(const VolumeEntry& entry, const std::filesystem::path& file);

// The bounds of the trilinear support of `file`'s grid, in scene world, from the
// file's metadata (the grid is read only when the metadata lacks its box).
Bounds read_vdb_bounds(const std::filesystem::path& file, const VolumeOptions& options);

}  // namespace avsm::scene
