#pragma once
// Reading the engine's own JSON files (capture reports, sweep indexes): typed
// accessors whose every failure names the key, and file reading whose every failure
// names the file. One writer per type (to_json) pairs with one reader built from these.
#include <nlohmann/json.hpp>

#include <filesystem>
#include <fstream>
#include <stdexcept>
#include <string>
#include <vector>

namespace avsm::capture {

inline const nlohmann::json& member(const nlohmann::json& object, const char* key) {
  if (!object.is_object()) throw std::runtime_error(std::string("expected an object holding \"") + key + "\"");
  const auto found = object.find(key);
  if (found == object.end()) throw std::runtime_error(std::string("no \"") + key + "\"");
  return *found;
}

template <class T>
T value_of(const nlohmann::json& object, const char* key) {
  try {
    return member(object, key).get<T>();
  } catch (const nlohmann::json::exception& e) {
    throw std::runtime_error(std::string("\"") + key + "\": " + e.what());
  }
}

// A number written as null where it had no value (no receivers, an infinite bound).
template <class T>
T number_or(const nlohmann::json& value, T fallback) {
  return value.is_null() ? fallback : value.get<T>();
}

// Each item read with `read`; an item's error is prefixed with "key[i]: ".
template <class T, class Read>
std::vector<T> array_of(const nlohmann::json& object, const char* key, Read read) {
  const nlohmann::json& items = member(object, key);
  if (!items.is_array()) throw std::runtime_error(std::string("\"") + key + "\": expected an array");
  std::vector<T> out;
  for (size_t i = 0; i < items.size(); ++i) {
    try {
      out.push_back(read(items[i]));
    } catch (const std::runtime_error& e) {
      throw std::runtime_error(std::string(key) + "[" + std::to_string(i) + "]: " + e.what());
    }
  }
  return out;
}

inline nlohmann::json read_json_file(const std::filesystem::path& path) {
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": missing or unreadable (run the capture first)");
  nlohmann::json parsed = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (parsed.is_discarded()) throw std::runtime_error(path.string() + ": not valid JSON");
  return parsed;
}

// Reads `path` with `from_json`, its errors prefixed with the path.
template <class Report>
Report read_report_file(const std::filesystem::path& path, Report (*from_json)(const nlohmann::json&)) {
  const nlohmann::json parsed = read_json_file(path);
  try {
    return from_json(parsed);
  } catch (const std::runtime_error& e) {
    throw std::runtime_error(path.string() + ": " + e.what());
  }
}

}  // namespace avsm::capture
