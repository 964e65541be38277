#pragma once
// Writing the capture's text outputs: one place that turns a failed write into an
// error naming the file.
#include <nlohmann/json_fwd.hpp>

#include <filesystem>
#include <string>

namespace avsm::capture {

// Throws std::runtime_error "<path>: cannot write".
void write_text(const std::filesystem::path& path, const std::string& text);
// `indent` as nlohmann::json::dump (-1: one line); ends with a newline.
void write_json(const std::filesystem::path& path, const nlohmann::json& json, int indent = 2);

}  // namespace avsm::capture
