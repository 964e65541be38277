#include "live/file_watcher.h"

namespace avsm::live {
namespace fs = std::filesystem;

void FileWatcher::watch(const std::vector<fs::path>& files) {
  std::map<fs::path, Entry> entries;
  for (const fs::path& file : files) {
    auto known = entries_.find(file);
    if (known != entries_.end()) {
      entries.insert(*known);
    } else {
      const io::FileStamp now = io::FileStamp::of(file);
      entries[file] = Entry{now, now, {}};  // when it changes, it is seen then
    }
  }
  entries_ = std::move(entries);
}

bool FileWatcher::observe(Clock::time_point now) {
  bool unchanged = true;
  for (auto& [file, entry] : entries_) {
    const io::FileStamp stamp = io::FileStamp::of(file);
    if (stamp == entry.seen) continue;
    entry.seen = stamp;
    entry.seen_since = now;
    unchanged = false;
  }
  return unchanged;
}

bool FileWatcher::settled(const Entry& entry, Clock::time_point now) const {
  const Clock::duration held = now - entry.seen_since;
  return held >= times_.settle && (entry.seen.exists || held >= times_.missing);
}

std::vector<fs::path> FileWatcher::settled_changes(Clock::time_point now) {
  observe(now);
  std::vector<fs::path> changed;
  busy_ = false;
  for (const auto& [file, entry] : entries_) {
    if (entry.seen == entry.read) continue;
    if (!settled(entry, now)) busy_ = true;
    changed.push_back(file);
  }
  if (busy_) changed.clear();
  return changed;
}

bool FileWatcher::confirm(Clock::time_point now) {
  // Changed during the read, or read while another change was still settling.
  busy_ = !observe(now);
  for (const auto& [file, entry] : entries_)
    if (entry.seen != entry.read && !settled(entry, now)) busy_ = true;
  if (busy_) return false;
  for (auto& [file, entry] : entries_) entry.read = entry.seen;
  return true;
}

std::vector<fs::path> FileWatcher::files() const {
  std::vector<fs::path> files;
  for (const auto& [file, entry] : entries_) files.push_back(file);
  return files;
}

}  // namespace avsm::live
