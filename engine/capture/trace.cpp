#include "capture/trace.h"

#include "capture/files.h"

#include <nlohmann/json.hpp>

#include <stdexcept>

namespace avsm::capture {

uint32_t TraceWriter::track_id(const std::string& track) {
  auto found = track_ids_.find(track);
  if (found != track_ids_.end()) return found->second;
  const uint32_t id = uint32_t(tracks_.size()) + 1;
  tracks_.push_back(track);
  track_ids_.emplace(track, id);
  return id;
}

void TraceWriter::add(const std::string& track, const std::string& name, double start_ms, double duration_ms,
                      const std::string& category) {
  events_.push_back({track_id(track), name, category, start_ms, duration_ms});
}

void TraceWriter::write(const std::filesystem::path& path) const {
  nlohmann::json events = nlohmann::json::array();
  events.push_back({{"name", "process_name"}, {"ph", "M"}, {"pid", 1}, {"args", {{"name", "avsm-capture"}}}});
  for (size_t i = 0; i < tracks_.size(); ++i) {
    events.push_back({{"name", "thread_name"}, {"ph", "M"}, {"pid", 1}, {"tid", i + 1}, {"args", {{"name", tracks_[i]}}}});
    events.push_back({{"name", "thread_sort_index"}, {"ph", "M"}, {"pid", 1}, {"tid", i + 1}, {"args", {{"sort_index", i}}}});
  }
  for (const Event& e : events_) {
    // Trace timestamps are microseconds.
    nlohmann::json event = {{"name", e.name}, {"ph", "X"}, {"pid", 1}, {"tid", e.track},
                            {"ts", e.start_ms * 1000.0}, {"dur", e.duration_ms * 1000.0}};
    if (!e.category.empty()) event["cat"] = e.category;
    events.push_back(event);
  }
  write_json(path, {{"traceEvents", events}, {"displayTimeUnit", "ms"}}, /*indent=*/-1);
}

}  // namespace avsm::capture
