#pragma once
// A file's modification time and size for change watching (shader cache, hot reload).
#include <cstdint>
#include <filesystem>

namespace avsm::io {

// The minimum time for a file that is missing or unreadable, so that a file which
// vanishes counts as changed.
inline std::filesystem::file_time_type write_time_or_min(const std::filesystem::path& file) {
  std::error_code ec;
  const std::filesystem::file_time_type time = std::filesystem::last_write_time(file, ec);
  return ec ? std::filesystem::file_time_type::min() : time;
}

// What a watcher compares to tell that a file changed: whether it is there, its size
// and its time stamp. The size catches a rewrite within the file system's time
// resolution that changed the length (a truncation, a chunk appended).
struct FileStamp {
  bool exists = false;
  std::uintmax_t size = 0;
  std::filesystem::file_time_type time = std::filesystem::file_time_type::min();

  static FileStamp of(const std::filesystem::path& file) {
    std::error_code ec;
    FileStamp stamp;
    stamp.time = std::filesystem::last_write_time(file, ec);
    if (ec) return {};
    stamp.size = std::filesystem::file_size(file, ec);
    if (ec) return {};
    stamp.exists = true;
    return stamp;
  }
  bool operator==(const FileStamp&) const = default;
};

}  // namespace avsm::io
