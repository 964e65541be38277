#pragma once
// Strict reading of the JSON files people write (scene files, sweep manifests): every
// value goes through a reader that knows its JSON path, so every message names the
// file, the path (e.g. "lights[1].shadow.nodes") and the problem, as a LoadError.
#include "scene/load_error.h"

#include <nlohmann/json.hpp>

#include <glm/glm.hpp>

#include <filesystem>
#include <optional>
#include <string>
#include <string_view>
#include <utility>
#include <vector>

namespace avsm::scene {

std::string child_path(const std::string& parent, const std::string& key);
std::string index_path(const std::string& parent, std::size_t index);
// "a string", "an integer", ...: for "expected X, got Y".
std::string describe_type(const nlohmann::json& value);

// Knows the file; every failure names it and the JSON path.
class Reader {
 public:
  explicit Reader(std::filesystem::path file) : file_(std::move(file)) {}
  const std::filesystem::path& file() const { return file_; }

  [[noreturn]] void fail(const std::string& path, const std::string& problem) const;
  void expect(bool condition, const std::string& path, const std::string& problem) const {
    if (!condition) fail(path, problem);
  }

  std::string string(const nlohmann::json& value, const std::string& path) const;
  bool boolean(const nlohmann::json& value, const std::string& path) const;
  double number(const nlohmann::json& value, const std::string& path) const;
  int integer(const nlohmann::json& value, const std::string& path) const;
  glm::vec3 vec3(const nlohmann::json& value, const std::string& path) const;

 private:
  std::filesystem::path file_;
};

// One JSON object: hands out its members and, at finish(), rejects any member
// nobody asked for (with the closest known key as a hint).
class ObjectReader {
 public:
  ObjectReader(const Reader& reader, const nlohmann::json& value, std::string path);

  const std::string& path() const { return path_; }
  std::string path_of(const std::string& key) const { return child_path(path_, key); }
  const Reader& reader() const { return reader_; }

  const nlohmann::json* optional(const std::string& key);
  const nlohmann::json& required(const std::string& key);
  bool has(const std::string& key) const { return value_.contains(key); }

  void finish() const;

  // Typed accessors.
  std::string string(const std::string& key) { return reader_.string(required(key), path_of(key)); }
  std::string string_or(const std::string& key, const std::string& fallback);
  float number(const std::string& key) { return float(reader_.number(required(key), path_of(key))); }
  float number_or(const std::string& key, float fallback);
  std::optional<float> optional_number(const std::string& key);
  int integer_or(const std::string& key, int fallback);
  std::optional<int> optional_integer(const std::string& key);
  bool boolean_or(const std::string& key, bool fallback);
  std::optional<bool> optional_boolean(const std::string& key);
  glm::vec3 vec3(const std::string& key) { return reader_.vec3(required(key), path_of(key)); }
  glm::vec3 vec3_or(const std::string& key, const glm::vec3& fallback);
  std::optional<glm::vec3> optional_vec3(const std::string& key);

  void check(bool condition, const std::string& key, const std::string& problem) const {
    reader_.expect(condition, path_of(key), problem);
  }

 private:
  const Reader& reader_;
  const nlohmann::json& value_;
  std::string path_;
  std::vector<std::string> known_;
};

// The member `key` as one of `options`' names (unset: nullopt); anything else fails,
// listing the names.
template <class Enum>
std::optional<Enum> optional_choice(ObjectReader& object, const std::string& key,
                                    const std::vector<std::pair<std::string, Enum>>& options) {
  const nlohmann::json* value = object.optional(key);
  if (value == nullptr) return std::nullopt;
  const std::string text = object.reader().string(*value, object.path_of(key));
  std::string allowed;
  for (const auto& [name, option] : options) {
    if (name == text) return option;
    allowed += (allowed.empty() ? "" : ", ") + name;
  }
  object.reader().fail(object.path_of(key), "'" + text + "' is not one of " + allowed);
}

template <class Enum>
Enum choice(ObjectReader& object, const std::string& key, Enum fallback,
            const std::vector<std::pair<std::string, Enum>>& options, bool is_required = false) {
  if (is_required) object.required(key);
  return optional_choice(object, key, options).value_or(fallback);
}

// Parses `text`, refusing repeated keys (nlohmann::json would keep the last); syntax
// errors are LoadErrors naming reader.file().
nlohmann::json parse_json(const Reader& reader, std::string_view text);

}  // namespace avsm::scene
