#include "scene/frame_pattern.h"

#include <algorithm>
#include <cctype>
#include <cmath>
#include <cstdio>
#include <stdexcept>
#include <vector>

namespace avsm::scene {
namespace {

struct Field {
  std::size_t begin = 0, end = 0;  // in the file name
  int digits = 0;
};

bool is_digit(char c) { return std::isdigit(static_cast<unsigned char>(c)) != 0; }

// Digits from `at` on, as a number (0 when there are none); `at` moves past them.
int read_number(const std::string& text, std::size_t& at) {
  int number = 0;
  for (; at < text.size() && is_digit(text[at]) && number < 100; ++at) number = number * 10 + (text[at] - '0');
  return number;
}

// The field starting at `at`, if one does: "#...#", "$F<n>", "%0<n>d" or "%d".
std::optional<Field> field_at(const std::string& name, std::size_t at) {
  if (name[at] == '#') {
    std::size_t end = at;
    while (end < name.size() && name[end] == '#') ++end;
    return Field{at, end, int(end - at)};
  }
  if (name.compare(at, 2, "$F") == 0) {
    std::size_t end = at + 2;
    const int digits = read_number(name, end);
    return Field{at, end, digits};
  }
  if (name[at] == '%') {
    std::size_t end = at + 1;
    const bool padded = end < name.size() && name[end] == '0';
    if (padded) ++end;
    const int digits = read_number(name, end);
    if (end < name.size() && name[end] == 'd' && (padded || digits == 0)) return Field{at, end + 1, padded ? digits : 0};
  }
  return std::nullopt;
}

}  // namespace

std::optional<FramePattern> parse_frame_pattern(const std::filesystem::path& file) {
  const std::string name = file.filename().string();
  std::vector<Field> fields;
  for (std::size_t at = 0; at < name.size();) {
    const std::optional<Field> field = field_at(name, at);
    if (!field) {
      ++at;
      continue;
    }
    fields.push_back(*field);
    at = field->end;
  }
  if (fields.empty()) return std::nullopt;
  if (fields.size() > 1)
    throw std::invalid_argument("'" + name + "' has " + std::to_string(fields.size()) +
                                " frame number fields; a sequence's file name has one (\"smoke.####.vdb\")");
  if (fields[0].digits > 9) throw std::invalid_argument("'" + name + "' pads frame numbers to more than 9 digits");
  FramePattern pattern;
  pattern.directory = file.parent_path();
  pattern.prefix = name.substr(0, fields[0].begin);
  pattern.suffix = name.substr(fields[0].end);
  pattern.digits = fields[0].digits;
  pattern.written = name;
  return pattern;
}

std::filesystem::path FramePattern::file(int frame) const {
  char number[32];
  std::snprintf(number, sizeof number, "%0*d", digits, frame);
  return directory / (prefix + number + suffix);
}

std::optional<int> FramePattern::frame_of(const std::string& file_name) const {
  if (file_name.size() <= prefix.size() + suffix.size() || file_name.compare(0, prefix.size(), prefix) != 0 ||
      file_name.compare(file_name.size() - suffix.size(), suffix.size(), suffix) != 0)
    return std::nullopt;
  const std::string number = file_name.substr(prefix.size(), file_name.size() - prefix.size() - suffix.size());
  if (number.size() > 9 || !std::all_of(number.begin(), number.end(), is_digit)) return std::nullopt;
  // Written by file(): exactly `digits` wide, or wider without a leading zero.
  const bool padded_as_written = int(number.size()) == std::max(digits, 1) || (int(number.size()) > digits && number[0] != '0');
  if (!padded_as_written) return std::nullopt;
  return std::stoi(number);
}

int SequenceTiming::frame_at(float time) const {
  // The small bias keeps time = n / fps on frame n despite rounding.
  const double steps = std::floor(double(time) * double(fps) + 1e-4);
  const long long frame = (long long)offset + (long long)std::clamp(steps, -1e9, 1e9);
  if (loop) {
    const long long n = count();
    return first + int(((frame - first) % n + n) % n);
  }
  return int(std::clamp<long long>(frame, first, last));
}

}  // namespace avsm::scene
