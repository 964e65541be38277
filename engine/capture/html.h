#pragma once
// What the self-contained HTML reports share: the single capture's report.html
// (capture/report.h) and the sweep's (sweep/sweep_report.h). Escaping, files embedded
// as data URIs, number formatting, the chart axes' steps and the page's head and style.
#include <cstdint>
#include <filesystem>
#include <ostream>
#include <string>
#include <string_view>

namespace avsm::capture {

// Text for HTML and SVG: &, <, >, " and ' escaped.
std::string escape_markup(std::string_view text);

// The whole file. Throws std::runtime_error naming it when missing ("the report needs
// it; run the capture first") or unreadable.
std::string read_file_bytes(const std::filesystem::path& path);

std::string base64(std::string_view bytes);

struct PngImage {
  std::string data_uri;            // data:image/png;base64,...
  uint32_t width = 0, height = 0;  // from the IHDR chunk; 0 when not a PNG
};
// Throws as read_file_bytes.
PngImage embed_png(const std::filesystem::path& path);

// In place of a value there is none of.
inline constexpr const char* kNoValue = "\u2013";

// printf's `pattern` with one double; kNoValue when it is not finite.
std::string format_value(const char* pattern, double value);
std::string ms_text(double value);             // "1.250 ms"
std::string bytes_short_text(uint64_t bytes);  // "2.00 MiB"
std::string bytes_text(uint64_t bytes);        // "2.00 MiB (2097152 B)"
std::string svg_number(double value);          // coordinates: "%.2f"

// A round step (1, 2 or 5 times a power of ten) giving about `ticks` ticks up to `max`.
double nice_step(double max, int ticks);

// <!DOCTYPE html> up to and including <body>: the title and the reports' style,
// followed by `extra_style` (CSS rules of the one page).
void write_html_head(std::ostream& html, std::string_view title, std::string_view extra_style = {});

}  // namespace avsm::capture
