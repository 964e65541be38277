#include "capture/files.h"

#include <fstream>
#include <nlohmann/json.hpp>
#include <stdexcept>

namespace avsm::capture {

void write_text(const std::filesystem::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  out << text;
  out.close();
  if (!out) throw std::runtime_error(path.string() + ": write failed (disk full?)");
}

void write_json(const std::filesystem::path& path, const nlohmann::json& json, int indent) {
  write_text(path, json.dump(indent) + "\n");
}

}  // namespace avsm::capture
