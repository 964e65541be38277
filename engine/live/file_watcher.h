#pragma once
// Watches files the way editors save them: writing in chunks after a truncation,
// writing a temporary file and renaming it over the original, deleting then
// recreating, or saving several times within milliseconds. A change is handed out
// only once it has settled (the file's size and time stamp held for `settle`), a
// file that vanished is taken for one being saved until `missing` has passed, and
// a read that overlapped a write is not taken as final (confirm()).
//
//   std::vector<path> changed = watcher.settled_changes(now);
//   if (!changed.empty()) {
//     read them...
//     if (watcher.confirm(now)) use or report what was read;
//     else drop it: a file changed while it was read, and comes back once settled.
//   }
// Time is passed in, so tests drive it without sleeping.
#include <chrono>
#include <filesystem>
#include <map>
#include <vector>

#include "io/file_time.h"

namespace avsm::live {

using Clock = std::chrono::steady_clock;

// How long a change must hold before it is read.
struct SettleTimes {
  // A changed file is read once its size and time stamp have not changed for this long
  // (0: at once, for tools that write whole files).
  Clock::duration settle = std::chrono::milliseconds(150);
  // A file that vanished is being saved (deleted then recreated) for this long; after
  // it, it counts as changed, and reading it reports it missing.
  Clock::duration missing = std::chrono::seconds(2);
};

class FileWatcher {
 public:
  explicit FileWatcher(SettleTimes times = {}) : times_(times) {}

  // Watches `files` from now on. Files watched already keep their state; the others
  // start from their content now, which counts as read.
  void watch(const std::vector<std::filesystem::path>& files);

  // The changed files, once every changed file has settled (all together, so a model's
  // .gltf and .bin are read as one); empty while nothing changed or a change is still
  // settling (busy()).
  std::vector<std::filesystem::path> settled_changes(Clock::time_point now);
  // A change seen by the last call is still settling: call again later.
  bool busy() const { return busy_; }

  // After reading what settled_changes() handed out: true when no watched file changed
  // while it was read and none is still settling, and what was read is now the content
  // to compare against (a failure to read it is then reported once, not again on
  // every poll). False otherwise: the read may have seen a half-written file, and the
  // changes come back once settled.
  bool confirm(Clock::time_point now);

  std::vector<std::filesystem::path> files() const;

 private:
  struct Entry {
    io::FileStamp read;             // the content last read (or last reported broken)
    io::FileStamp seen;             // the content now
    Clock::time_point seen_since;   // when `seen` was first observed
  };
  // Observes every file; false when one changed since the last look.
  bool observe(Clock::time_point now);
  bool settled(const Entry& entry, Clock::time_point now) const;

  SettleTimes times_;
  std::map<std::filesystem::path, Entry> entries_;
  bool busy_ = false;
};

}  // namespace avsm::live
