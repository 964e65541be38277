#include "sweep/gate_thresholds.h"

#include <nlohmann/json.hpp>
#include <stdexcept>
#include <string>
#include <variant>
#include <vector>

#include "capture/json_read.h"

namespace avsm::sweep {
namespace {
using nlohmann::json;

// One key of the file: where it lives in Thresholds, so reading and writing share
// one list of names.
struct Key {
  const char* section;
  const char* name;
  std::variant<double*, uint64_t*, bool*> value;
  double lowest;  // the smallest value that makes sense (numbers only)
};

std::vector<Key> keys_of(Thresholds& t) {
  return {
      {"timing", "max_pass_ratio", &t.timing.max_pass_ratio, 1.0},
      {"timing", "min_pass_ms", &t.timing.min_pass_ms, 0.0},
      {"timing", "min_pass_share", &t.timing.min_pass_share, 0.0},
      {"timing", "max_frame_ratio", &t.timing.max_frame_ratio, 1.0},
      {"timing", "judge_cpu_devices", &t.timing.judge_cpu_devices, 0.0},
      {"image", "min_psnr_db", &t.image.min_psnr_db, 0.0},
      {"image", "max_mean_abs_error", &t.image.max_mean_abs_error, 0.0},
      {"quality", "max_mean_abs_error_increase", &t.quality.max_mean_abs_error_increase, 0.0},
      {"memory", "max_ratio", &t.memory.max_ratio, 1.0},
      {"memory", "min_increase_bytes", &t.memory.min_increase_bytes, 0.0},
  };
}

const char* const kSections = "timing, image, quality, memory";

// The names of `section`'s keys, comma separated; empty for an unknown section.
std::string keys_in(const std::vector<Key>& keys, const std::string& section) {
  std::string list;
  for (const Key& key : keys)
    if (section == key.section) list += (list.empty() ? "" : ", ") + std::string(key.name);
  return list;
}

const Key* find_key(const std::vector<Key>& keys, const std::string& section, const std::string& name) {
  for (const Key& key : keys)
    if (section == key.section && name == key.name) return &key;
  return nullptr;
}

void read_key(const Key& key, const json& value) {
  const std::string path = std::string(key.section) + "." + key.name;
  if (auto* flag = std::get_if<bool*>(&key.value)) {
    if (!value.is_boolean()) throw std::runtime_error("\"" + path + "\": expected true or false");
    **flag = value.get<bool>();
    return;
  }
  if (!value.is_number()) throw std::runtime_error("\"" + path + "\": expected a number");
  const double number = value.get<double>();
  if (number < key.lowest)
    throw std::runtime_error("\"" + path + "\": " + value.dump() + " is below " + json(key.lowest).dump());
  if (auto* whole = std::get_if<uint64_t*>(&key.value)) {
    if (!value.is_number_integer()) throw std::runtime_error("\"" + path + "\": expected a whole number of bytes");
    **whole = value.get<uint64_t>();
  } else {
    *std::get<double*>(key.value) = number;
  }
}

}  // namespace

Thresholds thresholds_from_json(const json& in) {
  Thresholds t;
  const std::vector<Key> keys = keys_of(t);
  if (!in.is_object()) throw std::runtime_error(std::string("expected an object of sections (") + kSections + ")");
  for (const auto& [section, entries] : in.items()) {
    if (keys_in(keys, section).empty())
      throw std::runtime_error("unknown section \"" + section + "\" (known: " + kSections + ")");
    if (!entries.is_object()) throw std::runtime_error("\"" + section + "\": expected an object");
    for (const auto& [name, value] : entries.items()) {
      const Key* key = find_key(keys, section, name);
      if (!key)
        throw std::runtime_error("unknown key \"" + section + "." + name + "\" (known in \"" + section +
                                 "\": " + keys_in(keys, section) + ")");
      read_key(*key, value);
    }
  }
  return t;
}

json to_json(const Thresholds& thresholds) {
  Thresholds copy = thresholds;
  json out = json::object();
  for (const Key& key : keys_of(copy))
    std::visit([&](auto* value) { out[key.section][key.name] = *value; }, key.value);
  return out;
}

Thresholds read_thresholds(const std::filesystem::path& path) {
  std::error_code ec;
  if (!std::filesystem::is_regular_file(path, ec)) throw std::runtime_error(path.string() + ": no such file (--thresholds)");
  return capture::read_report_file(path, thresholds_from_json);
}

}  // namespace avsm::sweep
