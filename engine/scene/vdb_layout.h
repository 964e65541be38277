#pragma once
// Internal: a walk over the framing of an OpenVDB file (header, file metadata,
// grid descriptors with their byte ranges) without OpenVDB. OpenVDB does not
// check for the end of the stream while reading grid data: a truncated file
// loads "successfully" with zeros or garbage in place of the missing values,
// and absurd lengths in a corrupt header make it allocate or crash. Checking
// every length and offset here first turns those into LoadErrors.
#include <cstdint>
#include <filesystem>
#include <istream>
#include <string>
#include <vector>

namespace avsm::scene::detail {

struct VdbGridRecord {
  std::string unique_name;  // as stored; OpenVDB strips a "\x1e<n>" suffix for duplicates
  std::string type;         // e.g. "Tree_float_5_4_3", "_HalfFloat" appended when stored as half
  std::string instance_parent;
  std::uint64_t grid_pos = 0, block_pos = 0, end_pos = 0;
};

struct VdbLayout {
  std::uint32_t file_version = 0;
  std::vector<VdbGridRecord> grids;
};

// Throws LoadError(file, ...) unless `stream` (of `size` bytes) is a
// well-framed OpenVDB file with grid offsets whose grids all lie inside it.
VdbLayout read_vdb_layout(std::istream& stream, std::uint64_t size, const std::filesystem::path& file);

}  // namespace avsm::scene::detail
