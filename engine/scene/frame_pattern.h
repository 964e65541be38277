#pragma once
// Frame-number patterns in file names, and which frame of a sequence shows when
// (scene/volume_sequence.h plays volume sequences by them). No OpenVDB here.
#include <filesystem>
#include <optional>
#include <string>

namespace avsm::scene {

// A file name with one frame-number field, as the tools write them:
//   smoke.####.vdb     Houdini, EmberGen, Blender's fluid_data_####.vdb: one '#' per digit
//   smoke.$F4.vdb      Houdini's variable, padded to 4 digits ($F: not padded)
//   smoke.%04d.vdb     printf (%d: not padded)
struct FramePattern {
  std::filesystem::path directory;
  std::string prefix, suffix;  // of the file name, around the field
  int digits = 0;              // zero-padded to this many digits; 0: as many as the number needs

  std::filesystem::path file(int frame) const;
  // The frame a file name in `directory` holds, when it matches.
  std::optional<int> frame_of(const std::string& file_name) const;
  std::string written;         // the file name as the scene file gives it: "smoke.####.vdb"
};

// The pattern in `file`'s name, or nullopt when it has no frame field. Throws
// std::invalid_argument for a name with more than one field.
std::optional<FramePattern> parse_frame_pattern(const std::filesystem::path& file);

// Which file frame shows at a time (VolumeEntry's sequence settings).
struct SequenceTiming {
  int first = 0, last = 0;  // file frames, inclusive
  float fps = 24.0f;
  int offset = 0;     // the file frame shown at time 0
  bool loop = false;  // outside first..last: play again (true) or hold the end frame (false)

  int frame_at(float time) const;
  int count() const { return last - first + 1; }
};

}  // namespace avsm::scene
