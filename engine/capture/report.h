#pragma once
// The capture report: one self-contained HTML file (no external resources, no
// script) built from what run_capture wrote into its output folder: the frame and
// any per-light transmittance images, a per-pass GPU timing chart, the frame
// summary, the memory figures and the compiled frame graph. What --report writes.
#include <filesystem>
#include <string>
#include <string_view>

namespace avsm::capture {

// Reads frame.png, timings.json, graph.json, graph.dot and memory.json from
// out_dir (required: std::runtime_error naming a missing or unreadable one), and
// probes.json, light*_transmittance.png, quality.json with its light*_error.png
// and curve_*.svg when present; writes html_path.
void write_report(const std::filesystem::path& out_dir, const std::filesystem::path& html_path);

// Text for HTML and SVG: &, <, >, " and ' escaped.
std::string escape_markup(std::string_view text);

}  // namespace avsm::capture
