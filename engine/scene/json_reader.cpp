#include "scene/json_reader.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <set>

namespace avsm::scene {
namespace {

using json = nlohmann::json;

std::size_t edit_distance(const std::string& a, const std::string& b) {
  std::vector<std::size_t> row(b.size() + 1);
  for (std::size_t j = 0; j <= b.size(); ++j) row[j] = j;
  for (std::size_t i = 1; i <= a.size(); ++i) {
    std::size_t diagonal = row[0];
    row[0] = i;
    for (std::size_t j = 1; j <= b.size(); ++j) {
      const std::size_t above = row[j];
      row[j] = std::min({row[j] + 1, row[j - 1] + 1, diagonal + (a[i - 1] != b[j - 1])});
      diagonal = above;
    }
  }
  return row[b.size()];
}

// nlohmann::json keeps the last of repeated keys; a file with two "nodes" is a
// mistake, so the parse callback tracks the JSON path and refuses them.
class DuplicateKeyCheck {
 public:
  explicit DuplicateKeyCheck(const Reader& reader) : reader_(reader) {}

  bool operator()(int, json::parse_event_t event, json& parsed) {
    switch (event) {
      case json::parse_event_t::object_start: frames_.push_back({}); break;
      case json::parse_event_t::array_start: frames_.push_back({true}); break;
      case json::parse_event_t::key: {
        Frame& frame = frames_.back();
        frame.key = parsed.get<std::string>();
        if (!frame.keys.insert(frame.key).second) reader_.fail(path(), "duplicate key");
        break;
      }
      case json::parse_event_t::value: element_done(); break;
      case json::parse_event_t::object_end:
      case json::parse_event_t::array_end:
        frames_.pop_back();
        element_done();
        break;
    }
    return true;
  }

 private:
  struct Frame {
    bool is_array = false;
    std::size_t index = 0;
    std::string key;
    std::set<std::string> keys;
  };
  void element_done() {
    if (!frames_.empty() && frames_.back().is_array) ++frames_.back().index;
  }
  std::string path() const {
    std::string result;
    for (const Frame& frame : frames_) result = frame.is_array ? index_path(result, frame.index) : child_path(result, frame.key);
    return result;
  }

  const Reader& reader_;
  std::vector<Frame> frames_;
};

}  // namespace

std::string child_path(const std::string& parent, const std::string& key) {
  return parent.empty() ? key : parent + "." + key;
}
std::string index_path(const std::string& parent, std::size_t index) {
  return parent + "[" + std::to_string(index) + "]";
}

std::string describe_type(const json& value) {
  switch (value.type()) {
    case json::value_t::null: return "null";
    case json::value_t::boolean: return "true/false";
    case json::value_t::string: return "a string";
    case json::value_t::array: return "an array";
    case json::value_t::object: return "an object";
    case json::value_t::number_float: return "a number with a fraction";
    case json::value_t::number_integer:
    case json::value_t::number_unsigned: return "an integer";
    default: return "something else";
  }
}

// ---- Reader ----

void Reader::fail(const std::string& path, const std::string& problem) const {
  throw LoadError(file_, (path.empty() ? std::string("top level") : path) + ": " + problem);
}

std::string Reader::string(const json& value, const std::string& path) const {
  expect(value.is_string(), path, "expected a string, got " + describe_type(value));
  return value.get<std::string>();
}
bool Reader::boolean(const json& value, const std::string& path) const {
  expect(value.is_boolean(), path, "expected true or false, got " + describe_type(value));
  return value.get<bool>();
}
double Reader::number(const json& value, const std::string& path) const {
  expect(value.is_number(), path, "expected a number, got " + describe_type(value));
  const double result = value.get<double>();
  expect(std::isfinite(result), path, "expected a finite number");
  return result;
}
int Reader::integer(const json& value, const std::string& path) const {
  expect(value.is_number_integer(), path, "expected a whole number, got " + describe_type(value));
  constexpr std::int64_t kLimit = 1 << 30;
  const bool in_range = value.is_number_unsigned() ? value.get<std::uint64_t>() <= std::uint64_t(kLimit)
                                                   : std::abs(value.get<std::int64_t>()) <= kLimit;
  expect(in_range, path, "number is out of range");
  return static_cast<int>(value.get<std::int64_t>());
}
glm::vec3 Reader::vec3(const json& value, const std::string& path) const {
  expect(value.is_array() && value.size() == 3, path, "expected an array of 3 numbers, got " + describe_type(value) +
                                                          (value.is_array() ? " of " + std::to_string(value.size()) : ""));
  return glm::vec3(float(number(value[0], index_path(path, 0))), float(number(value[1], index_path(path, 1))),
                   float(number(value[2], index_path(path, 2))));
}

// ---- ObjectReader ----

ObjectReader::ObjectReader(const Reader& reader, const json& value, std::string path)
    : reader_(reader), value_(value), path_(std::move(path)) {
  reader_.expect(value.is_object(), path_, "expected an object, got " + describe_type(value));
}

const json* ObjectReader::optional(const std::string& key) {
  if (std::find(known_.begin(), known_.end(), key) == known_.end()) known_.push_back(key);
  const auto found = value_.find(key);
  return found == value_.end() ? nullptr : &*found;
}

const json& ObjectReader::required(const std::string& key) {
  const json* value = optional(key);
  if (value == nullptr) reader_.fail(path_of(key), "required key is missing");
  return *value;
}

void ObjectReader::finish() const {
  for (const auto& [key, unused] : value_.items()) {
    if (std::find(known_.begin(), known_.end(), key) != known_.end()) continue;
    std::string hint;
    std::size_t best = 3;  // suggest only near misses
    for (const std::string& candidate : known_)
      if (const std::size_t d = edit_distance(key, candidate); d < best) best = d, hint = candidate;
    std::string known_list;
    for (const std::string& candidate : known_) known_list += (known_list.empty() ? "" : ", ") + candidate;
    reader_.fail(path_of(key), "unknown key" + (hint.empty() ? "" : " (did you mean '" + hint + "'?)") +
                                   "; allowed here: " + known_list);
  }
}

std::string ObjectReader::string_or(const std::string& key, const std::string& fallback) {
  const json* value = optional(key);
  return value ? reader_.string(*value, path_of(key)) : fallback;
}
float ObjectReader::number_or(const std::string& key, float fallback) {
  return optional_number(key).value_or(fallback);
}
std::optional<float> ObjectReader::optional_number(const std::string& key) {
  const json* value = optional(key);
  return value ? std::optional<float>(float(reader_.number(*value, path_of(key)))) : std::nullopt;
}
int ObjectReader::integer_or(const std::string& key, int fallback) { return optional_integer(key).value_or(fallback); }
std::optional<int> ObjectReader::optional_integer(const std::string& key) {
  const json* value = optional(key);
  return value ? std::optional<int>(reader_.integer(*value, path_of(key))) : std::nullopt;
}
bool ObjectReader::boolean_or(const std::string& key, bool fallback) { return optional_boolean(key).value_or(fallback); }
std::optional<bool> ObjectReader::optional_boolean(const std::string& key) {
  const json* value = optional(key);
  return value ? std::optional<bool>(reader_.boolean(*value, path_of(key))) : std::nullopt;
}
glm::vec3 ObjectReader::vec3_or(const std::string& key, const glm::vec3& fallback) {
  return optional_vec3(key).value_or(fallback);
}
std::optional<glm::vec3> ObjectReader::optional_vec3(const std::string& key) {
  const json* value = optional(key);
  return value ? std::optional<glm::vec3>(reader_.vec3(*value, path_of(key))) : std::nullopt;
}

json parse_json(const Reader& reader, std::string_view text) {
  try {
    DuplicateKeyCheck check(reader);
    return json::parse(text.begin(), text.end(), std::ref(check));
  } catch (const json::exception& error) {  // parse_error, and out_of_range for numbers like 1e999
    std::string message = error.what();
    if (const auto bracket = message.find("] "); message.rfind("[json.exception", 0) == 0 && bracket != std::string::npos)
      message.erase(0, bracket + 2);
    throw LoadError(reader.file(), "invalid JSON: " + message);
  }
}

}  // namespace avsm::scene
