#pragma once
// Chrome trace event format (chrome://tracing, ui.perfetto.dev): complete ("X")
// events on named tracks, written as one JSON file.
#include <cstdint>
#include <filesystem>
#include <map>
#include <string>
#include <vector>

namespace avsm::capture {

class TraceWriter {
 public:
  // Tracks appear in the order they are first used.
  void add(const std::string& track, const std::string& name, double start_ms, double duration_ms,
           const std::string& category = "");
  void write(const std::filesystem::path& path) const;
  size_t event_count() const { return events_.size(); }

 private:
  struct Event {
    uint32_t track;
    std::string name, category;
    double start_ms, duration_ms;
  };
  uint32_t track_id(const std::string& track);
  std::vector<std::string> tracks_;
  std::map<std::string, uint32_t> track_ids_;
  std::vector<Event> events_;
};

}  // namespace avsm::capture
