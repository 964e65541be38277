#pragma once
// A file's modification time for change watching (shader cache, hot reload).
#include <filesystem>

namespace avsm::io {

// The minimum time for a file that is missing or unreadable, so that a file which
// vanishes counts as changed.
inline std::filesystem::file_time_type write_time_or_min(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::file_time_type time = std::filesystem::last_write_time(file, ec);
  return ec ? std::filesystem::file_time_type::min() : time;
}

}  // namespace avsm::io
