#include "capture/report.h"

#include <algorithm>
#include <cmath>
#include <cstdint>
#include <cstdio>
#include <fstream>
#include <initializer_list>
#include <iterator>
#include <map>
#include <optional>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

namespace avsm::capture {
namespace fs = std::filesystem;

namespace {

// ---- files ----

std::string read_bytes(const fs::path& path) {
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

struct PngImage {
  std::string data_uri;
  uint32_t width = 0, height = 0;  // from the IHDR chunk; 0 when not a PNG
};

PngImage embed_png(const fs::path& path) {
  const std::string bytes = read_bytes(path);
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

// light<i>_transmittance.png in out_dir, by light index.
std::vector<std::pair<long, fs::path>> light_images(const fs::path& out_dir) {
  static const std::string kPrefix = "light", kSuffix = "_transmittance.png";
  std::vector<std::pair<long, fs::path>> found;
  std::error_code ec;
  for (fs::directory_iterator it(out_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.size() <= kPrefix.size() + kSuffix.size() || name.compare(0, kPrefix.size(), kPrefix) != 0 ||
        name.compare(name.size() - kSuffix.size(), kSuffix.size(), kSuffix) != 0 || !it->is_regular_file(ec))
      continue;
    const std::string middle = name.substr(kPrefix.size(), name.size() - kPrefix.size() - kSuffix.size());
    long index = -1;
    if (!middle.empty() && middle.size() < 9 && std::all_of(middle.begin(), middle.end(), [](char c) {
          return c >= '0' && c <= '9';
        }))
      index = std::stol(middle);
    found.emplace_back(index, it->path());
  }
  std::sort(found.begin(), found.end(), [](const auto& a, const auto& b) {
    return a.first != b.first ? a.first < b.first : a.second.filename() < b.second.filename();
  });
  return found;
}

// ---- text ----

std::string escape(std::string_view text) { return escape_markup(text); }

const char* const kDash = "\u2013";  // in place of a value there is none of

std::string format(const char* pattern, double value) {
  if (!std::isfinite(value)) return "\u2013";
  char buffer[64];
  std::snprintf(buffer, sizeof buffer, pattern, value);
  return buffer;
}

std::string ms(double value) { return std::isfinite(value) ? format("%.3f", value) + " ms" : kDash; }

std::string bytes_text(uint64_t bytes) {
  const double b = double(bytes);
  std::string human;
  if (b >= 1024.0 * 1024 * 1024) human = format("%.2f GiB", b / (1024.0 * 1024 * 1024));
  else if (b >= 1024.0 * 1024) human = format("%.2f MiB", b / (1024.0 * 1024));
  else if (b >= 1024.0) human = format("%.1f KiB", b / 1024.0);
  else return std::to_string(bytes) + " B";
  return human + " (" + std::to_string(bytes) + " B)";
}

const char* queue_colour(rg::QueueType queue) {
  switch (queue) {
    case rg::QueueType::Graphics: return "#4e79a7";
    case rg::QueueType::Compute: return "#f28e2b";
    case rg::QueueType::Transfer: return "#59a14f";
  }
  return "#9c9c9c";
}

std::string spread_text(const Spread& s) {
  return ms(s.median) + " median (" + ms(s.min) + " \u2013 " + ms(s.max) + ")";
}

// As JSON spells them: what the report said when it read graph.json.
std::string bool_text(bool value) { return value ? "true" : "false"; }

// A round step (1, 2 or 5 times a power of ten) giving about `ticks` ticks up to `max`.
double nice_step(double max, int ticks) {
  if (!(max > 0)) return 1;
  const double raw = max / ticks;
  const double power = std::pow(10.0, std::floor(std::log10(raw)));
  for (double m : {1.0, 2.0, 5.0})
    if (raw <= m * power) return m * power;
  return 10 * power;
}

// ---- sections ----

void write_head(std::ostringstream& html, const TimingReport& timings) {
  html << "<!DOCTYPE html>\n<html lang=\"en\">\n<head>\n<meta charset=\"utf-8\">\n"
       << "<title>avsm-capture report: " << escape(timings.device) << "</title>\n"
       << "<style>\n"
          "body{font:14px/1.4 system-ui,sans-serif;margin:1.5em auto;max-width:1100px;padding:0 1em;color:#222}\n"
          "h1{font-size:1.5em}h2{font-size:1.2em;margin-top:1.6em;border-bottom:1px solid #ddd}\n"
          "table{border-collapse:collapse;margin:.5em 0}th,td{padding:2px 8px;border-bottom:1px solid #eee;"
          "text-align:left;vertical-align:top}\n"
          "td.num,th.num{text-align:right;font-variant-numeric:tabular-nums}\n"
          "tr.group th{background:#f4f4f4}\n"
          "img{image-rendering:pixelated}#frame-image{width:100%;max-width:960px;height:auto;border:1px solid #ccc}\n"
          "#light-images{display:flex;flex-wrap:wrap;gap:1em}figure{margin:0}\n"
          "img.light-map{width:256px;height:auto;border:1px solid #ccc}\n"
          "svg text{font:12px system-ui,sans-serif}\n"
          "pre{background:#f7f7f7;padding:.5em;overflow:auto;max-height:40em}\n"
          ".note{color:#666}\n"
          "</style>\n</head>\n<body>\n";
}

void write_frame(std::ostringstream& html, const fs::path& out_dir, const TimingReport& timings) {
  const PngImage frame = embed_png(out_dir / "frame.png");
  html << "<h1>avsm-capture report</h1>\n<p class=\"note\">" << escape(out_dir.string()) << "</p>\n"
       << "<section>\n<h2>Frame</h2>\n<img id=\"frame-image\" alt=\"frame.png\"";
  if (frame.width && frame.height) html << " width=\"" << frame.width << "\" height=\"" << frame.height << "\"";
  html << " src=\"" << frame.data_uri << "\">\n";

  auto row = [&](const std::string& name, const std::string& value) {
    html << "<tr><th>" << escape(name) << "</th><td>" << escape(value) << "</td></tr>\n";
  };
  html << "<table id=\"frame-summary\">\n";
  row("device", timings.device);
  row("driver", timings.driver);
  row("timestamps", timings.timestamp_mode);
  row("size", std::to_string(timings.width) + " \u00d7 " + std::to_string(timings.height));
  row("frames measured", std::to_string(timings.frames.size()));
  row("frame GPU time", spread_text(timings.frame_gpu_ms));
  row("frame wall time", spread_text(timings.frame_wall_ms));
  row("frame submit to completion", spread_text(timings.frame_submit_wall_ms));
  html << "</table>\n</section>\n";
}

void write_light_images(std::ostringstream& html, const fs::path& out_dir,
                        const std::vector<passes::LightShadowStats>& lights) {
  html << "<section>\n<h2>Light transmittance</h2>\n<div id=\"light-images\">\n";
  const auto images = light_images(out_dir);
  for (const auto& [index, path] : images) {
    const PngImage image = embed_png(path);
    std::string caption = path.filename().string();
    if (index >= 0 && size_t(index) < lights.size())
      caption = "light " + std::to_string(index) + ": " + lights[size_t(index)].light;
    if (image.width && image.height)
      caption += " (" + std::to_string(image.width) + "\u00d7" + std::to_string(image.height) + ")";
    html << "<figure><img class=\"light-map\" alt=\"" << escape(path.filename().string()) << "\" src=\""
         << image.data_uri << "\"><figcaption>" << escape(caption) << "</figcaption></figure>\n";
  }
  html << "</div>\n";
  if (images.empty()) html << "<p class=\"note\">No light*_transmittance.png in the folder.</p>\n";
  html << "</section>\n";
}

void write_timing_chart(std::ostringstream& html, const TimingReport& timings) {
  struct Bar {
    std::string name;
    rg::QueueType queue;
    double median, min, max, cpu;
  };
  std::vector<Bar> bars;
  double scale_max = 0, total = 0;
  size_t longest_name = 4;
  for (const PassTiming& pass : timings.passes) {
    Bar bar{pass.name, pass.queue, pass.gpu_ms.median, pass.gpu_ms.min, pass.gpu_ms.max, pass.cpu_record_ms.median};
    for (double v : {bar.median, bar.min, bar.max})
      if (std::isfinite(v)) scale_max = std::max(scale_max, v);
    if (std::isfinite(bar.median)) total += bar.median;
    longest_name = std::max(longest_name, bar.name.size());
    bars.push_back(std::move(bar));
  }

  const double label_w = std::clamp(double(longest_name) * 7.0 + 12, 120.0, 360.0);
  const double plot_w = 560, value_w = 170, row_h = 20, top = 26, bottom = 30;
  const double width = label_w + plot_w + value_w;
  const double height = top + row_h * double(bars.size()) + bottom;
  const double step = nice_step(scale_max, 5);
  const double axis_max = scale_max > 0 ? std::ceil(scale_max / step - 1e-9) * step : 1;
  auto x_of = [&](double v) { return label_w + (std::isfinite(v) ? std::max(v, 0.0) : 0.0) / axis_max * plot_w; };
  auto num = [](double v) { return format("%.2f", v); };

  html << "<section>\n<h2>GPU time per pass</h2>\n<p class=\"note\">Median over the measured frames; whiskers "
          "span min \u2013 max. Sum of medians: "
       << escape(ms(total)) << ".</p>\n"
       << "<svg id=\"timing-chart\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << num(width) << "\" height=\""
       << num(height) << "\" viewBox=\"0 0 " << num(width) << " " << num(height)
       << "\" role=\"img\" aria-label=\"GPU time per pass\">\n";
  // Axis: grid lines and tick labels in ms.
  for (int k = 0; double(k) * step <= axis_max + step * 1e-6; ++k) {
    const double t = double(k) * step, x = x_of(t);
    const bool last = double(k + 1) * step > axis_max + step * 1e-6;
    html << "<line x1=\"" << num(x) << "\" y1=\"" << num(top - 4) << "\" x2=\"" << num(x) << "\" y2=\""
         << num(top + row_h * double(bars.size())) << "\" stroke=\"#e3e3e3\"/>"
         << "<text x=\"" << num(x) << "\" y=\"" << num(top - 8) << "\" text-anchor=\"middle\" fill=\"#666\">"
         << escape(format(step < 1 ? "%.2f" : "%.0f", t)) << (last ? " ms" : "") << "</text>\n";
  }
  for (size_t i = 0; i < bars.size(); ++i) {
    const Bar& bar = bars[i];
    const double y = top + row_h * double(i), mid = y + row_h / 2;
    const std::string tooltip = bar.name + " (" + rg::to_string(bar.queue) + "): " + ms(bar.median) + " median, " + ms(bar.min) +
                                " min, " + ms(bar.max) + " max; CPU record " + ms(bar.cpu);
    html << "<text x=\"" << num(label_w - 6) << "\" y=\"" << num(mid + 4) << "\" text-anchor=\"end\">"
         << escape(bar.name) << "</text>"
         << "<rect x=\"" << num(label_w) << "\" y=\"" << num(y + 3) << "\" width=\""
         << num(x_of(bar.median) - label_w) << "\" height=\"" << num(row_h - 6) << "\" fill=\""
         << queue_colour(bar.queue) << "\"><title>" << escape(tooltip) << "</title></rect>";
    if (std::isfinite(bar.min) && std::isfinite(bar.max)) {
      const double x0 = x_of(bar.min), x1 = x_of(bar.max);
      html << "<path d=\"M" << num(x0) << " " << num(mid) << "H" << num(x1) << "M" << num(x0) << " " << num(mid - 4)
           << "V" << num(mid + 4) << "M" << num(x1) << " " << num(mid - 4) << "V" << num(mid + 4)
           << "\" stroke=\"#333\" fill=\"none\"/>";
    }
    std::string value = ms(bar.median);
    if (total > 0 && std::isfinite(bar.median)) value += format(" (%.1f%%)", bar.median / total * 100);
    html << "<text x=\"" << num(label_w + plot_w + 8) << "\" y=\"" << num(mid + 4) << "\">" << escape(value)
         << "</text>\n";
  }
  // Legend: one swatch per queue that appears.
  std::vector<rg::QueueType> queues;
  for (const Bar& bar : bars)
    if (std::find(queues.begin(), queues.end(), bar.queue) == queues.end()) queues.push_back(bar.queue);
  double legend_x = label_w;
  const double legend_y = top + row_h * double(bars.size()) + 18;
  for (const rg::QueueType queue : queues) {
    const std::string name = rg::to_string(queue);
    html << "<circle cx=\"" << num(legend_x + 5) << "\" cy=\"" << num(legend_y - 4) << "\" r=\"5\" fill=\""
         << queue_colour(queue) << "\"/><text x=\"" << num(legend_x + 14) << "\" y=\"" << num(legend_y) << "\">"
         << escape(name) << "</text>\n";
    legend_x += 24 + 7.0 * double(name.size()) + 12;
  }
  html << "</svg>\n";
  if (bars.empty()) html << "<p class=\"note\">No pass was timed.</p>\n";
  html << "</section>\n";
}

void write_memory(std::ostringstream& html, const MemoryReport& memory) {
  const uint64_t aliased = memory.transient_bytes_aliased, unaliased = memory.transient_bytes_unaliased;
  std::string saving = kDash;
  if (unaliased > 0)
    saving = format("%.1f%%", (double(unaliased) - double(aliased)) / double(unaliased) * 100) + ": " +
             bytes_text(unaliased >= aliased ? unaliased - aliased : 0);

  static const char* kLightColumns[] = {"light",    "technique", "nodes",           "resolution",
                                        "mips",     "map",       "capture buffer",  "segments requested",
                                        "capacity", "next capacity", "overflowed"};
  const int columns = int(std::size(kLightColumns));
  html << "<section>\n<h2>Memory</h2>\n<table id=\"memory-table\">\n<tbody>\n";
  auto row = [&](const std::string& name, const std::string& value) {
    html << "<tr><th colspan=\"3\">" << escape(name) << "</th><td colspan=\"" << columns - 3 << "\">" << escape(value)
         << "</td></tr>\n";
  };
  row("transient memory without aliasing", bytes_text(unaliased));
  row("transient memory with aliasing", bytes_text(aliased));
  row("saved by aliasing", saving);
  row("heaps", std::to_string(memory.heap_count));
  row("frames with capture overflow", std::to_string(memory.frames_with_capture_overflow));

  html << "<tr class=\"group\">";
  for (const char* column : kLightColumns) html << "<th>" << column << "</th>";
  html << "</tr>\n";
  uint64_t light_total = 0;
  for (const passes::LightShadowStats& light : memory.lights) {
    light_total += light.map_bytes + light.capture_bytes;
    html << "<tr class=\"light\"><td>" << escape(light.light) << "</td><td>"
         << escape(light.technique) << "</td>";
    for (uint64_t value : {light.nodes, light.resolution, light.mip_levels})
      html << "<td class=\"num\">" << value << "</td>";
    html << "<td class=\"num\">" << escape(bytes_text(light.map_bytes)) << "</td><td class=\"num\">"
         << escape(bytes_text(light.capture_bytes)) << "</td>";
    for (uint64_t value : {light.capture_requested, light.capture_capacity, light.next_capture_capacity})
      html << "<td class=\"num\">" << value << "</td>";
    html << "<td>" << (light.overflowed ? "yes" : "no") << "</td></tr>\n";
  }
  if (memory.lights.empty()) html << "<tr><td colspan=\"" << columns << "\" class=\"note\">no lights</td></tr>\n";
  else
    html << "<tr><th>all lights</th><td colspan=\"4\"></td><td class=\"num\" colspan=\"2\">"
         << escape(bytes_text(light_total)) << " (maps + capture buffers)</td><td colspan=\"4\"></td></tr>\n";
  html << "</tbody>\n</table>\n</section>\n";
}

void write_probes(std::ostringstream& html, const ProbeReport& probes) {
  html << "<section>\n<h2>Probes</h2>\n<table id=\"probes-table\">\n<tr><th>point</th>";
  for (const ProbeLight& light : probes.lights)
    html << "<th class=\"num\">" << escape(light.light) << " (" << escape(light.settings.technique)
         << ")</th>";
  html << "</tr>\n";
  for (size_t p = 0; p < probes.points.size(); ++p) {
    const glm::vec3& point = probes.points[p];
    const std::string coordinates =
        format("%.4g", point.x) + ", " + format("%.4g", point.y) + ", " + format("%.4g", point.z);
    html << "<tr><td>(" << escape(coordinates) << ")</td>";
    for (const ProbeLight& light : probes.lights)
      html << "<td class=\"num\">"
           << (p < light.transmittance.size() ? format("%.4f", light.transmittance[p]) : kDash) << "</td>";
    html << "</tr>\n";
  }
  html << "</table>\n</section>\n";
}

// curve_<light>_<x>_<y>.svg in out_dir (avsm-capture --plot-texel), by name.
std::vector<fs::path> curve_plots(const fs::path& out_dir) {
  std::vector<fs::path> found;
  std::error_code ec;
  for (fs::directory_iterator it(out_dir, ec), end; !ec && it != end; it.increment(ec)) {
    const std::string name = it->path().filename().string();
    if (name.rfind("curve_", 0) == 0 && it->path().extension() == ".svg" && it->is_regular_file(ec))
      found.push_back(it->path());
  }
  std::sort(found.begin(), found.end());
  return found;
}

std::string error_text(const ErrorStats& errors, double value) {
  return errors.receivers ? format("%.4f", value) : kDash;
}
std::string mean_text(const ErrorStats& errors) { return error_text(errors, errors.mean()); }
std::string max_text(const ErrorStats& errors) { return error_text(errors, errors.max); }

// Per light (--compare-to uncompressed) its errors against the exact reference and
// its error image.
void write_quality_table(std::ostringstream& html, const fs::path& out_dir, const QualityReport& quality) {
  html << "<p class=\"note\">|T &minus; T<sub>exact</sub>| against each light's capture lists at the receivers "
          "the camera sees; images: error \u00d7"
       << format("%g", kErrorImageScale) << ", " << escape(kErrorImageColours)
       << ". Hair: " << escape(hair_receivers_rule()) << ".</p>\n"
       << "<table id=\"quality-table\">\n<tr><th>light</th><th>technique</th><th class=\"num\">receivers</th>"
          "<th class=\"num\">mean</th><th class=\"num\">max</th><th class=\"num\">surface mean / max</th>"
          "<th class=\"num\">smoke mean / max</th></tr>\n";
  for (const LightQuality& light : quality.lights) {
    const ErrorStats all = light.all();
    const std::string receivers = std::to_string(all.receivers) + " (" + std::to_string(light.surface.receivers) +
                                  " + " + std::to_string(light.smoke.receivers) + ")";
    html << "<tr><td>" << escape(light.light) << "</td><td>" << escape(technique_label(light.settings))
         << "</td><td class=\"num\">" << escape(receivers) << "</td><td class=\"num\">" << mean_text(all)
         << "</td><td class=\"num\">" << max_text(all) << "</td><td class=\"num\">" << mean_text(light.surface)
         << " / " << max_text(light.surface) << "</td><td class=\"num\">" << mean_text(light.smoke) << " / "
         << max_text(light.smoke) << "</td></tr>\n";
  }
  html << "</table>\n<div id=\"quality-images\" style=\"display:flex;flex-wrap:wrap;gap:1em\">\n";
  for (size_t i = 0; i < quality.lights.size(); ++i) {
    const std::string file = error_image_name(i);
    std::error_code ec;
    if (!fs::is_regular_file(out_dir / file, ec)) continue;
    html << "<figure><img class=\"error-image\" style=\"width:320px;height:auto;border:1px solid #ccc\" alt=\""
         << escape(file) << "\" src=\"" << embed_png(out_dir / file).data_uri << "\"><figcaption>"
         << escape(quality.lights[i].light + ": " + technique_label(quality.lights[i].settings) + " error")
         << "</figcaption></figure>\n";
  }
  html << "</div>\n";
}

// The quality table when measured, then the texel curves (--plot-texel) as images.
void write_quality(std::ostringstream& html, const fs::path& out_dir, const std::optional<QualityReport>& quality,
                   const std::vector<fs::path>& curves) {
  html << "<section>\n<h2>Shadow quality</h2>\n";
  if (quality) write_quality_table(html, out_dir, *quality);
  if (!curves.empty()) {
    html << "<div id=\"texel-curves\">\n";
    for (const fs::path& path : curves)
      html << "<figure><img class=\"texel-curve\" style=\"max-width:100%\" alt=\""
           << escape(path.filename().string()) << "\" src=\"data:image/svg+xml;base64," << base64(read_bytes(path))
           << "\"></figure>\n";
    html << "</div>\n";
  }
  html << "</section>\n";
}

std::string hex(uint64_t value) {
  char text[20];
  std::snprintf(text, sizeof text, "%llx", (unsigned long long)value);
  return text;
}

std::string index_text(std::optional<uint32_t> index) { return index ? std::to_string(*index) : kDash; }

void write_graph(std::ostringstream& html, const PlanSummary& plan, const std::string& dot,
                 const TimingReport& timings) {
  auto pass_name = [&](std::optional<uint32_t> index) -> std::string {
    if (!index || *index >= plan.passes.size()) return index_text(index);
    return std::to_string(*index) + " " + plan.passes[*index].name;
  };

  html << "<section>\n<h2>Frame graph</h2>\n<p>" << plan.passes.size() << " passes, " << plan.culled_passes.size()
       << " culled, " << plan.barrier_count << " barriers (" << plan.final_barrier_count
       << " after the last pass); aliasing " << bool_text(plan.options.aliasing) << ", culling "
       << bool_text(plan.options.culling) << "; shape hash " << hex(plan.shape_hash) << ".</p>\n";

  html << "<table id=\"graph-passes\">\n<tr><th class=\"num\">#</th><th>pass</th><th>queue</th>"
          "<th class=\"num\">barriers</th><th class=\"num\">GPU median</th></tr>\n";
  for (size_t i = 0; i < plan.passes.size(); ++i) {
    const PlanPassSummary& pass = plan.passes[i];
    const std::optional<double> median = timings.median_gpu_ms(pass.name);
    html << "<tr><td class=\"num\">" << i << "</td><td>" << escape(pass.name) << "</td><td>"
         << rg::to_string(pass.queue) << "</td><td class=\"num\">" << pass.barrier_count
         << "</td><td class=\"num\">" << escape(median ? ms(*median) : kDash) << "</td></tr>\n";
  }
  html << "</table>\n";
  if (!plan.culled_passes.empty()) {
    html << "<p>Culled (never recorded):";
    for (const std::string& name : plan.culled_passes) html << " " << escape(name) << ";";
    html << "</p>\n";
  }

  html << "<h3>Transient resources</h3>\n<table id=\"graph-resources\">\n<tr><th class=\"num\">#</th><th>resource</th>"
          "<th>kind</th><th>description</th><th class=\"num\">size</th><th class=\"num\">heap</th>"
          "<th class=\"num\">offset</th><th>first pass</th><th>last pass</th></tr>\n";
  std::vector<std::string> imported;
  for (size_t r = 0; r < plan.resources.size(); ++r) {
    const PlanResourceSummary& resource = plan.resources[r];
    if (resource.imported) {
      imported.push_back(resource.name);
      continue;
    }
    html << "<tr><td class=\"num\">" << r << "</td><td>" << escape(resource.name) << "</td><td>"
         << rg::to_string(resource.kind) << "</td><td>" << escape(resource.description) << "</td><td class=\"num\">"
         << escape(bytes_text(resource.size)) << "</td><td class=\"num\">" << escape(index_text(resource.heap))
         << "</td><td class=\"num\">" << resource.offset << "</td>";
    if (!resource.used) html << "<td colspan=\"2\" class=\"note\">unused</td></tr>\n";
    else
      html << "<td>" << escape(pass_name(resource.first_pass)) << "</td><td>" << escape(pass_name(resource.last_pass))
           << "</td></tr>\n";
  }
  html << "</table>\n";
  if (!imported.empty()) {
    html << "<p class=\"note\">Imported (owned outside the graph):";
    for (size_t i = 0; i < imported.size(); ++i) html << (i ? ", " : " ") << escape(imported[i]);
    html << ".</p>\n";
  }
  html << "<details><summary>graph.dot (Graphviz source)</summary>\n<pre id=\"graph-dot\">" << escape(dot)
       << "</pre>\n</details>\n</section>\n";
}

void write_footer(std::ostringstream& html, const fs::path& out_dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(out_dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) && it->path().extension() != ".html") names.push_back(it->path().filename().string());
  std::sort(names.begin(), names.end());
  html << "<footer>\n<p class=\"note\">Written by avsm-capture --report. Files in the folder:";
  for (size_t i = 0; i < names.size(); ++i) html << (i ? ", " : " ") << escape(names[i]);
  html << ".</p>\n</footer>\n</body>\n</html>\n";
}

}  // namespace

void write_report(const fs::path& out_dir, const FrameReport& report, const fs::path& html_path) {
  const std::vector<fs::path> curves = curve_plots(out_dir);
  std::ostringstream html;
  write_head(html, report.timings);
  write_frame(html, out_dir, report.timings);
  write_light_images(html, out_dir, report.memory.lights);
  write_timing_chart(html, report.timings);
  write_memory(html, report.memory);
  if (report.probes) write_probes(html, *report.probes);
  if (report.quality || !curves.empty()) write_quality(html, out_dir, report.quality, curves);
  write_graph(html, report.plan, report.plan_dot, report.timings);
  write_footer(html, out_dir);

  std::ofstream out(html_path, std::ios::binary);
  if (!out) throw std::runtime_error(html_path.string() + ": cannot write");
  out << html.str();
  out.close();
  if (!out) throw std::runtime_error(html_path.string() + ": write failed");
}

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

}  // namespace avsm::capture
