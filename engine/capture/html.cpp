#include "capture/html.h"

#include <cmath>
#include <cstdio>
#include <fstream>
#include <iterator>
#include <stdexcept>

namespace avsm::capture {
namespace fs = std::filesystem;

std::string escape_markup(std::string_view text) {
  std::string out;
  out.reserve(text.size());
  for (char c : text) {
    switch (c) {
      case '&': out += "&amp;"; break;
      case '<': out += "&lt;"; break;
      case '>': out += "&gt;"; break;
      case '"': out += "&quot;"; break;
      case '\'': out += "&#39;"; break;
      default: out += c;
    }
  }
  return out;
}

std::string read_file_bytes(const fs::path& path) {
  std::error_code ec;
  if (!fs::is_regular_file(path, ec))
    throw std::runtime_error(path.string() + ": missing (the report needs it; run the capture first)");
  std::ifstream in(path, std::ios::binary);
  if (!in) throw std::runtime_error(path.string() + ": cannot read");
  return std::string(std::istreambuf_iterator<char>(in), std::istreambuf_iterator<char>());
}

std::string base64(std::string_view bytes) {
  static const char kAlphabet[] = "ABCDEFGHIJKLMNOPQRSTUVWXYZabcdefghijklmnopqrstuvwxyz0123456789+/";
  std::string out;
  out.reserve((bytes.size() + 2) / 3 * 4);
  size_t i = 0;
  for (; i + 3 <= bytes.size(); i += 3) {
    const uint32_t n = uint32_t(uint8_t(bytes[i])) << 16 | uint32_t(uint8_t(bytes[i + 1])) << 8 | uint8_t(bytes[i + 2]);
    out += kAlphabet[n >> 18 & 63];
    out += kAlphabet[n >> 12 & 63];
    out += kAlphabet[n >> 6 & 63];
    out += kAlphabet[n & 63];
  }
  if (const size_t rest = bytes.size() - i; rest > 0) {
    uint32_t n = uint32_t(uint8_t(bytes[i])) << 16;
    if (rest == 2) n |= uint32_t(uint8_t(bytes[i + 1])) << 8;
    out += kAlphabet[n >> 18 & 63];
    out += kAlphabet[n >> 12 & 63];
    out += rest == 2 ? kAlphabet[n >> 6 & 63] : '=';
    out += '=';
  }
  return out;
}

PngImage embed_png(const fs::path& path) {
  const std::string bytes = read_file_bytes(path);
  PngImage image;
  image.data_uri = "data:image/png;base64," + base64(bytes);
  static const char kSignature[] = "\x89PNG\r\n\x1a\n";
  if (bytes.size() >= 24 && bytes.compare(0, 8, kSignature, 8) == 0 && bytes.compare(12, 4, "IHDR") == 0) {
    auto be32 = [&](size_t at) {
      return uint32_t(uint8_t(bytes[at])) << 24 | uint32_t(uint8_t(bytes[at + 1])) << 16 |
             uint32_t(uint8_t(bytes[at + 2])) << 8 | uint8_t(bytes[at + 3]);
    };
    image.width = be32(16);
    image.height = be32(20);
  }
  return image;
}

std::string format_value(const char* pattern, double value) {
  if (!std::isfinite(value)) return kNoValue;
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string ms_text(double value) { return std::isfinite(value) ? format_value("%.3f", value) + " ms" : kNoValue; }

std::string bytes_short_text(uint64_t bytes) {
  const double b = double(bytes);
  if (b >= 1024.0 * 1024 * 1024) return format_value("%.2f GiB", b / (1024.0 * 1024 * 1024));
  if (b >= 1024.0 * 1024) return format_value("%.2f MiB", b / (1024.0 * 1024));
  if (b >= 1024.0) return format_value("%.1f KiB", b / 1024.0);
  return std::to_string(bytes) + " B";
}

std::string bytes_text(uint64_t bytes) {
  if (bytes < 1024) return bytes_short_text(bytes);
  return bytes_short_text(bytes) + " (" + std::to_string(bytes) + " B)";
}

std::string svg_number(double value) { return format_value("%.2f", value); }

double nice_step(double max, int ticks) {
  if (!(max > 0)) return 1;
  const double raw = max / ticks;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (raw <= m * power) return m * power;
  return 10 * power;
}

void write_html_head(std::ostream& html, std::string_view title, std::string_view extra_style) {
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       << "<title>" << escape_markup(title) << "</title>\n"
       << "<style>\n"
          "body{font:14px/1.4 system-ui,sans-serif;margin:1.5em auto;max-width:1100px;padding:0 1em;color:#222}\n"
          "h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ddd}\n"
          "table{border-collapse:collapse;margin:.5em 0}th,td{padding:2px 8px;border-bottom:1px solid #eee;"
          "text-align:left;vertical-align:top}\n"
          "td.num,th.num{text-align:right;font-variant-numeric:tabular-nums}\n"
          "tr.group th{background:#f4f4f4}\n"
          "img{image-rendering:pixelated}figure{margin:0}\n"
          "svg text{font:12px system-ui,sans-serif}\n"
          "pre{background:#f7f7f7;padding:.5em;overflow:auto;max-height:40em}\n"
          ".note{color:#666}\n"
       << extra_style << "</style>\n</head>\n<body>\n";
}

}  // namespace avsm::capture
