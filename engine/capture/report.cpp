#include "capture/report.h"

#include "capture/files.h"
#include "capture/html.h"

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

const char* queue_colour(rg::QueueType queue) {
  switch (queue) {
    case rg::QueueType::Graphics: return "#4e79a7";
    case rg::QueueType::Compute: return "#f28e2b";
    case rg::QueueType::Transfer: return "#59a14f";
  }
  return "#9c9c9c";
}

std::string spread_text(const Spread& s) {
  return ms_text(s.median) + " median (" + ms_text(s.min) + " \u2013 " + ms_text(s.max) + ")";
}

// As JSON spells them: what the report said when it read graph.json.
std::string bool_text(bool value) { return value ? "true" : "false"; }

// ---- sections ----

void write_head(std::ostringstream& html, const TimingReport& timings) {
  write_html_head(html, "avsm-capture report: " + timings.device,
                  "#frame-image{width:100%;max-width:960px;height:auto;border:1px solid #ccc}\n"
                  "#light-images{display:flex;flex-wrap:wrap;gap:1em}\n"
                  "img.light-map{width:256px;height:auto;border:1px solid #ccc}\n"
                  "#contact-sheet{display:flex;flex-wrap:wrap;gap:0.5em}\n"
                  "#contact-sheet figure{margin:0;font-size:12px}\n");
}

void write_frame(std::ostringstream& html, const fs::path& out_dir, const TimingReport& timings) {
  const PngImage frame = embed_png(out_dir / "frame.png");
  html << "<h1>avsm-capture report</h1>\n<p class=\"note\">" << escape_markup(out_dir.string()) << "</p>\n"
       << "<section>\n<h2>Frame</h2>\n<img id=\"frame-image\" alt=\"frame.png\"";
  if (frame.width && frame.height) html << " width=\"" << frame.width << "\" height=\"" << frame.height << "\"";
  html << " src=\"" << frame.data_uri << "\">\n";

  auto row = [&](const std::string& name, const std::string& value) {
    html << "<tr><th>" << escape_markup(name) << "</th><td>" << escape_markup(value) << "</td></tr>\n";
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
    html << "<figure><img class=\"light-map\" alt=\"" << escape_markup(path.filename().string()) << "\" src=\""
         << image.data_uri << "\"><figcaption>" << escape_markup(caption) << "</figcaption></figure>\n";
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
  auto num = svg_number;

  html << "<section>\n<h2>GPU time per pass</h2>\n<p class=\"note\">Median over the measured frames; whiskers "
          "span min \u2013 max. Sum of medians: "
       << escape_markup(ms_text(total)) << ".</p>\n"
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
         << escape_markup(format_value(step < 1 ? "%.2f" : "%.0f", t)) << (last ? " ms" : "") << "</text>\n";
  }
  for (size_t i = 0; i < bars.size(); ++i) {
    const Bar& bar = bars[i];
    const double y = top + row_h * double(i), mid = y + row_h / 2;
    const std::string tooltip = bar.name + " (" + rg::to_string(bar.queue) + "): " + ms_text(bar.median) + " median, " + ms_text(bar.min) +
                                " min, " + ms_text(bar.max) + " max; CPU record " + ms_text(bar.cpu);
    html << "<text x=\"" << num(label_w - 6) << "\" y=\"" << num(mid + 4) << "\" text-anchor=\"end\">"
         << escape_markup(bar.name) << "</text>"
         << "<rect x=\"" << num(label_w) << "\" y=\"" << num(y + 3) << "\" width=\""
         << num(x_of(bar.median) - label_w) << "\" height=\"" << num(row_h - 6) << "\" fill=\""
         << queue_colour(bar.queue) << "\"><title>" << escape_markup(tooltip) << "</title></rect>";
    if (std::isfinite(bar.min) && std::isfinite(bar.max)) {
      const double x0 = x_of(bar.min), x1 = x_of(bar.max);
      html << "<path d=\"M" << num(x0) << " " << num(mid) << "H" << num(x1) << "M" << num(x0) << " " << num(mid - 4)
           << "V" << num(mid + 4) << "M" << num(x1) << " " << num(mid - 4) << "V" << num(mid + 4)
           << "\" stroke=\"#333\" fill=\"none\"/>";
    }
    std::string value = ms_text(bar.median);
    if (total > 0 && std::isfinite(bar.median)) value += format_value(" (%.1f%%)", bar.median / total * 100);
    html << "<text x=\"" << num(label_w + plot_w + 8) << "\" y=\"" << num(mid + 4) << "\">" << escape_markup(value)
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
         << escape_markup(name) << "</text>\n";
    legend_x += 24 + 7.0 * double(name.size()) + 12;
  }
  html << "</svg>\n";
  if (bars.empty()) html << "<p class=\"note\">No pass was timed.</p>\n";
  html << "</section>\n";
}

void write_memory(std::ostringstream& html, const MemoryReport& memory) {
  const uint64_t aliased = memory.transient_bytes_aliased, unaliased = memory.transient_bytes_unaliased;
  std::string saving = kNoValue;
  if (unaliased > 0)
    saving = format_value("%.1f%%", (double(unaliased) - double(aliased)) / double(unaliased) * 100) + ": " +
             bytes_text(unaliased >= aliased ? unaliased - aliased : 0);

  static const char* kLightColumns[] = {"light",    "technique", "nodes",           "resolution",
                                        "mips",     "map",       "capture buffer",  "segments requested",
                                        "capacity", "next capacity", "overflowed"};
  const int columns = int(std::size(kLightColumns));
  html << "<section>\n<h2>Memory</h2>\n<table id=\"memory-table\">\n<tbody>\n";
  auto row = [&](const std::string& name, const std::string& value) {
    html << "<tr><th colspan=\"3\">" << escape_markup(name) << "</th><td colspan=\"" << columns - 3 << "\">" << escape_markup(value)
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
    html << "<tr class=\"light\"><td>" << escape_markup(light.light) << "</td><td>"
         << escape_markup(light.technique) << "</td>";
    for (uint64_t value : {light.nodes, light.resolution, light.mip_levels})
      html << "<td class=\"num\">" << value << "</td>";
    html << "<td class=\"num\">" << escape_markup(bytes_text(light.map_bytes)) << "</td><td class=\"num\">"
         << escape_markup(bytes_text(light.capture_bytes)) << "</td>";
    for (uint64_t value : {light.capture_requested, light.capture_capacity, light.next_capture_capacity})
      html << "<td class=\"num\">" << value << "</td>";
    html << "<td>" << (light.overflowed ? "yes" : "no") << "</td></tr>\n";
  }
  if (memory.lights.empty()) html << "<tr><td colspan=\"" << columns << "\" class=\"note\">no lights</td></tr>\n";
  else
    html << "<tr><th>all lights</th><td colspan=\"4\"></td><td class=\"num\" colspan=\"2\">"
         << escape_markup(bytes_text(light_total)) << " (maps + capture buffers)</td><td colspan=\"4\"></td></tr>\n";
  html << "</tbody>\n</table>\n</section>\n";
}

void write_probes(std::ostringstream& html, const ProbeReport& probes) {
  html << "<section>\n<h2>Probes</h2>\n<table id=\"probes-table\">\n<tr><th>point</th>";
  for (const ProbeLight& light : probes.lights)
    html << "<th class=\"num\">" << escape_markup(light.light) << " (" << escape_markup(light.settings.technique)
         << ")</th>";
  html << "</tr>\n";
  for (size_t p = 0; p < probes.points.size(); ++p) {
    const glm::vec3& point = probes.points[p];
    const std::string coordinates =
        format_value("%.4g", point.x) + ", " + format_value("%.4g", point.y) + ", " + format_value("%.4g", point.z);
    html << "<tr><td>(" << escape_markup(coordinates) << ")</td>";
    for (const ProbeLight& light : probes.lights)
      html << "<td class=\"num\">"
           << (p < light.transmittance.size() ? format_value("%.4f", light.transmittance[p]) : kNoValue) << "</td>";
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
  return errors.receivers ? format_value("%.4f", value) : kNoValue;
}
std::string mean_text(const ErrorStats& errors) { return error_text(errors, errors.mean()); }
std::string max_text(const ErrorStats& errors) { return error_text(errors, errors.max); }

// Per light (--compare-to uncompressed) its errors against the exact reference and
// its error image.
void write_quality_table(std::ostringstream& html, const fs::path& out_dir, const QualityReport& quality) {
  html << "<p class=\"note\">|T &minus; T<sub>exact</sub>| against each light's capture lists at the receivers "
          "the camera sees; images: error \u00d7"
       << format_value("%g", kErrorImageScale) << ", " << escape_markup(kErrorImageColours)
       << ". Hair: " << escape_markup(hair_receivers_rule()) << ".</p>\n"
       << "<table id=\"quality-table\">\n<tr><th>light</th><th>technique</th><th class=\"num\">receivers</th>"
          "<th class=\"num\">mean</th><th class=\"num\">max</th><th class=\"num\">surface mean / max</th>"
          "<th class=\"num\">smoke mean / max</th></tr>\n";
  for (const LightQuality& light : quality.lights) {
    const ErrorStats all = light.all();
    const std::string receivers = std::to_string(all.receivers) + " (" + std::to_string(light.surface.receivers) +
                                  " + " + std::to_string(light.smoke.receivers) + ")";
    html << "<tr><td>" << escape_markup(light.light) << "</td><td>" << escape_markup(technique_label(light.settings))
         << "</td><td class=\"num\">" << escape_markup(receivers) << "</td><td class=\"num\">" << mean_text(all)
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
         << escape_markup(file) << "\" src=\"" << embed_png(out_dir / file).data_uri << "\"><figcaption>"
         << escape_markup(quality.lights[i].light + ": " + technique_label(quality.lights[i].settings) + " error")
         << "</figcaption></figure>\n";
  }
  html << "</div>\n";
}

// Per light (--measure-resolution) how wide on screen the texels the surfaces read are,
// and its picture.
void write_resolution(std::ostringstream& html, const fs::path& out_dir, const ResolutionReport& resolution) {
  html << "<section>\n<h2>Shadow resolution</h2>\n<p class=\"note\">The widest a texel of the level each lit "
          "surface pixel's lookup reads is on screen; matched: at most "
       << format_value("%g", kMatchedTexelPixels) << " pixels. Images: " << escape_markup(kResolutionImageColours)
       << ". All lights: " << format_value("%.1f", 100.0 * resolution.matched_fraction()) << "% of "
       << resolution.receivers() << " receivers matched.</p>\n"
       << "<table id=\"resolution-table\">\n<tr><th>light</th><th>layout</th><th class=\"num\">receivers</th>"
          "<th class=\"num\">matched</th><th class=\"num\">median px</th><th class=\"num\">95th percentile px</th></tr>\n";
  for (const LightResolution& light : resolution.lights)
    html << "<tr><td>" << escape_markup(light.light) << "</td><td>" << (light.paged ? "paged" : "dense")
         << "</td><td class=\"num\">" << light.receivers << "</td><td class=\"num\">"
         << format_value("%.1f%%", 100.0 * light.matched_fraction()) << "</td><td class=\"num\">"
         << format_value("%.2f", light.median_texel_pixels) << "</td><td class=\"num\">"
         << format_value("%.2f", light.p95_texel_pixels) << "</td></tr>\n";
  html << "</table>\n<div id=\"resolution-images\" style=\"display:flex;flex-wrap:wrap;gap:1em\">\n";
  for (size_t i = 0; i < resolution.lights.size(); ++i) {
    const std::string file = resolution_image_name(i);
    std::error_code ec;
    if (!fs::is_regular_file(out_dir / file, ec)) continue;
    html << "<figure><img class=\"resolution-image\" style=\"width:320px;height:auto;border:1px solid #ccc\" alt=\""
         << escape_markup(file) << "\" src=\"" << embed_png(out_dir / file).data_uri << "\"><figcaption>"
         << escape_markup(resolution.lights[i].light + ": texel width on screen") << "</figcaption></figure>\n";
  }
  html << "</div>\n</section>\n";
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
           << escape_markup(path.filename().string()) << "\" src=\"data:image/svg+xml;base64," << base64(read_file_bytes(path))
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

std::string index_text(std::optional<uint32_t> index) { return index ? std::to_string(*index) : kNoValue; }

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
    html << "<tr><td class=\"num\">" << i << "</td><td>" << escape_markup(pass.name) << "</td><td>"
         << rg::to_string(pass.queue) << "</td><td class=\"num\">" << pass.barrier_count
         << "</td><td class=\"num\">" << escape_markup(median ? ms_text(*median) : kNoValue) << "</td></tr>\n";
  }
  html << "</table>\n";
  if (!plan.culled_passes.empty()) {
    html << "<p>Culled (never recorded):";
    for (const std::string& name : plan.culled_passes) html << " " << escape_markup(name) << ";";
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
    html << "<tr><td class=\"num\">" << r << "</td><td>" << escape_markup(resource.name) << "</td><td>"
         << rg::to_string(resource.kind) << "</td><td>" << escape_markup(resource.description) << "</td><td class=\"num\">"
         << escape_markup(bytes_text(resource.size)) << "</td><td class=\"num\">" << escape_markup(index_text(resource.heap))
         << "</td><td class=\"num\">" << resource.offset << "</td>";
    if (!resource.used) html << "<td colspan=\"2\" class=\"note\">unused</td></tr>\n";
    else
      html << "<td>" << escape_markup(pass_name(resource.first_pass)) << "</td><td>" << escape_markup(pass_name(resource.last_pass))
           << "</td></tr>\n";
  }
  html << "</table>\n";
  if (!imported.empty()) {
    html << "<p class=\"note\">Imported (owned outside the graph):";
    for (size_t i = 0; i < imported.size(); ++i) html << (i ? ", " : " ") << escape_markup(imported[i]);
    html << ".</p>\n";
  }
  html << "<details><summary>graph.dot (Graphviz source)</summary>\n<pre id=\"graph-dot\">" << escape_markup(dot)
       << "</pre>\n</details>\n</section>\n";
}

// A shot: each frame's wall time as a bar (the first, kept apart, in grey), a contact
// sheet of up to 24 frames spread over the shot, and its video or why there is none.
void write_shot(std::ostringstream& html, const fs::path& out_dir, const ShotReport& shot) {
  const ShotSummary summary = shot.summary();
  html << "<section>\n<h2>Shot</h2>\n<p>Frames " << shot.range.first << " to " << shot.range.last << " at "
       << format_value("%g", shot.range.fps) << " fps: the first " << format_value("%.1f", summary.first_ms)
       << " ms (kept apart), then " << format_value("%.1f", summary.mean_ms) << " ms on average, median "
       << format_value("%.1f", summary.median_ms) << ", slowest " << format_value("%.1f", summary.max_ms) << " (frame "
       << summary.slowest_frame << ").</p>\n";
  double highest = 1e-9;
  for (const ShotFrame& f : shot.frames) highest = std::max(highest, f.wall_ms);
  const double width = 720.0, height = 160.0, bar = width / double(std::max<size_t>(shot.frames.size(), 1));
  html << "<svg id=\"shot-timings\" width=\"" << width << "\" height=\"" << height + 20 << "\" role=\"img\" "
       << "aria-label=\"wall ms per shot frame\">\n";
  for (size_t i = 0; i < shot.frames.size(); ++i) {
    const ShotFrame& f = shot.frames[i];
    const double h = height * f.wall_ms / highest;
    html << "<rect x=\"" << bar * double(i) << "\" y=\"" << height - h << "\" width=\"" << std::max(bar - 1.0, 1.0)
         << "\" height=\"" << h << "\" fill=\"" << (i == 0 ? "#999" : "#4a7bd0") << "\"><title>frame " << f.frame << ": "
         << format_value("%.2f", f.wall_ms) << " ms</title></rect>\n";
  }
  html << "<text x=\"0\" y=\"" << height + 16 << "\" font-size=\"12\">wall ms per frame (tallest "
       << format_value("%.1f", highest) << "); grey: the first frame</text>\n</svg>\n";
  html << "<div id=\"contact-sheet\">\n";
  const size_t shown = std::min<size_t>(shot.frames.size(), 24);
  for (size_t k = 0; k < shown; ++k) {
    const size_t i = shown > 1 ? k * (shot.frames.size() - 1) / (shown - 1) : 0;
    const ShotFrame& f = shot.frames[i];
    html << "<figure><img width=\"160\" alt=\"frame " << f.frame << "\" src=\"" << embed_png(out_dir / f.image).data_uri
         << "\"><figcaption>" << f.frame << " (" << format_value("%.3f", f.time) << " s)</figcaption></figure>\n";
  }
  html << "</div>\n";
  if (!shot.video.empty())
    html << "<p><a href=\"" << escape_markup(shot.video.generic_string()) << "\">" << escape_markup(shot.video.generic_string())
         << "</a></p>\n";
  else
    html << "<p class=\"note\">" << escape_markup(shot.video_note) << "</p>\n";
  html << "</section>\n";
}

void write_footer(std::ostringstream& html, const fs::path& out_dir) {
  std::vector<std::string> names;
  std::error_code ec;
  for (fs::directory_iterator it(out_dir, ec), end; !ec && it != end; it.increment(ec))
    if (it->is_regular_file(ec) && it->path().extension() != ".html") names.push_back(it->path().filename().string());
  std::sort(names.begin(), names.end());
  html << "<footer>\n<p class=\"note\">Written by avsm-capture --report. Files in the folder:";
  for (size_t i = 0; i < names.size(); ++i) html << (i ? ", " : " ") << escape_markup(names[i]);
  html << ".</p>\n</footer>\n</body>\n</html>\n";
}

}  // namespace

void write_report(const fs::path& out_dir, const FrameReport& report, const fs::path& html_path) {
  const std::vector<fs::path> curves = curve_plots(out_dir);
  std::ostringstream html;
  write_head(html, report.timings);
  write_frame(html, out_dir, report.timings);
  if (report.shot) write_shot(html, out_dir, *report.shot);
  write_light_images(html, out_dir, report.memory.lights);
  write_timing_chart(html, report.timings);
  write_memory(html, report.memory);
  if (report.probes) write_probes(html, *report.probes);
  if (report.quality || !curves.empty()) write_quality(html, out_dir, report.quality, curves);
  if (report.resolution) write_resolution(html, out_dir, *report.resolution);
  write_graph(html, report.plan, report.plan_dot, report.timings);
  write_footer(html, out_dir);

  write_text(html_path, html.str());
}

}  // namespace avsm::capture
