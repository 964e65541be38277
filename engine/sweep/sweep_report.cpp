#include "sweep/sweep_report.h"

#include <algorithm>
#include <cmath>
#include <nlohmann/json.hpp>
#include <sstream>
#include <stdexcept>
#include <string>
#include <string_view>
#include <vector>

#include "capture/files.h"
#include "capture/html.h"
#include "capture/quality.h"

namespace avsm::sweep {
namespace fs = std::filesystem;
using capture::escape_markup;
using capture::format_value;
using capture::kNoValue;
using capture::svg_number;

namespace {

// ---- reading the jobs ----

std::string label_of(const scene::ShadowSettings& settings) {
  try {
    return capture::technique_label(settings);
  } catch (const std::exception&) {
    return settings.technique;  // not a technique this build knows: its name as the manifest gave it
  }
}

void add_unique(std::vector<std::string>& list, const std::string& item) {
  if (std::find(list.begin(), list.end(), item) == list.end()) list.push_back(item);
}

std::string joined(const std::vector<std::string>& items, std::string_view separator) {
  std::string out;
  for (size_t i = 0; i < items.size(); ++i) out += (i ? std::string(separator) : "") + items[i];
  return out;
}

// What the job rendered: its lights' techniques as quality.json records them (whole
// settings), else the manifest's technique override, else memory.json's technique names.
std::string technique_of(const JobRecord& job, const std::optional<capture::FrameReport>& frame) {
  std::vector<std::string> labels;
  if (frame && frame->quality)
    for (const capture::LightQuality& light : frame->quality->lights) add_unique(labels, label_of(light.settings));
  if (labels.empty() && job.settings.shadow.technique) {
    scene::ShadowSettings settings;
    job.settings.shadow.apply(settings);
    labels.push_back(label_of(settings));
  }
  if (labels.empty() && frame)
    for (const passes::LightShadowStats& light : frame->memory.lights) add_unique(labels, light.technique);
  return labels.empty() ? "scene's own" : joined(labels, ", ");
}

JobResult read_job(const fs::path& sweep_dir, const JobRecord& job) {
  JobResult result;
  result.job = job;
  if (job.status == JobStatus::done) {
    try {
      result.frame = capture::read_frame_report(sweep_dir / job.output);
    } catch (const std::exception& e) {
      result.problem = e.what();
    }
  }
  if (result.frame) {
    result.stage_ms = capture::stage_gpu_ms(result.frame->timings);
    if (result.frame->quality) {
      capture::ErrorStats all;
      for (const capture::LightQuality& light : result.frame->quality->lights) all.add(light.all());
      result.shadow_error = all;
    }
  }
  result.technique = technique_of(job, result.frame);
  return result;
}

// frame.exr against the reference job's, or why not.
void compare_to_reference(const fs::path& sweep_dir, JobResult& result, const std::vector<JobResult>& results) {
  const std::string& reference_id = result.job.settings.reference_job;
  if (reference_id.empty() || !result.frame) return;
  const auto reference =
      std::find_if(results.begin(), results.end(), [&](const JobResult& r) { return r.job.id == reference_id; });
  if (reference == results.end()) {
    result.image_error_problem = "reference job '" + reference_id + "' is not in the sweep";
  } else if (!reference->frame) {
    result.image_error_problem =
        "reference job '" + reference_id + "' has no capture (" + std::string(to_string(reference->job.status)) + ")";
  } else {
    try {
      result.image_error = capture::exr_difference(sweep_dir / result.job.output / "frame.exr",
                                                   sweep_dir / reference->job.output / "frame.exr");
    } catch (const std::exception& e) {
      result.image_error_problem = e.what();
    }
  }
}

// ---- text ----

// The scene file's name without ".scene.json" (or ".json").
std::string scene_name(const JobSettings& settings) {
  if (settings.scene.empty()) return "default scene";
  std::string name = fs::path(settings.scene).filename().string();
  for (std::string_view suffix : {".scene.json", ".json"})
    if (name.size() > suffix.size() && name.compare(name.size() - suffix.size(), suffix.size(), suffix) == 0)
      return name.substr(0, name.size() - suffix.size());
  return name;
}

// The manifest's shadow overrides but the technique (the table's column of its own) as
// "nodes 8, resolution 64, slices=32".
std::string overrides_text(const scene::ShadowOverrides& shadow) {
  std::vector<std::string> parts;
  auto value_text = [](const nlohmann::json& value) {
    return value.is_string() ? value.get<std::string>() : value.dump();
  };
  const nlohmann::json overrides = to_json(shadow);
  for (const auto& [key, value] : overrides.items()) {
    if (key == "technique") continue;
    if (value.is_object())
      for (const auto& [name, number] : value.items()) parts.push_back(name + "=" + value_text(number));
    else
      parts.push_back(key + " " + value_text(value));
  }
  return joined(parts, ", ");
}

// Size, frames, camera, the shadow overrides and the reference job.
std::string settings_text(const JobSettings& s) {
  std::string text = std::to_string(s.width) + "\u00d7" + std::to_string(s.height) + ", " + std::to_string(s.frames) +
                     (s.frames == 1 ? " frame" : " frames");
  if (!s.camera.empty()) text += ", camera " + s.camera;
  if (const std::string overrides = overrides_text(s.shadow); !overrides.empty()) text += ", " + overrides;
  if (!s.reference_job.empty()) text += "; vs " + s.reference_job;
  return text;
}

std::string status_text(const JobRecord& job) {
  std::string text(to_string(job.status));
  if (job.exit_code && (job.status == JobStatus::failed || *job.exit_code != 0))
    text += " (exit " + std::to_string(*job.exit_code) + ")";
  return text;
}

uint64_t map_bytes(const capture::MemoryReport& memory) {
  uint64_t sum = 0;
  for (const passes::LightShadowStats& light : memory.lights) sum += light.map_bytes;
  return sum;
}

// The lists, or the fixed build's depth image and hair bins: what a light's map needs
// besides itself while it is built.
uint64_t build_bytes(const capture::MemoryReport& memory) {
  uint64_t sum = 0;
  for (const passes::LightShadowStats& light : memory.lights)
    sum += light.capture_bytes + (light.fixed_build ? light.fixed_build->transient_bytes() : 0);
  return sum;
}

std::string number_cell(const std::string& text, const std::string& title = {}) {
  std::string cell = "<td class=\"num\"";
  if (!title.empty()) cell += " title=\"" + escape_markup(title) + "\"";
  return cell + ">" + escape_markup(text) + "</td>";
}

std::string bytes_cell(uint64_t bytes) {
  return number_cell(capture::bytes_short_text(bytes), std::to_string(bytes) + " bytes");
}

std::string psnr_text(double psnr_db) {
  return std::isinf(psnr_db) ? "\u221e dB (equal)" : format_value("%.2f dB", psnr_db);
}

// ---- sections ----

const char* const kStyle =
    "body{max-width:1600px}\n"
    ".wide{overflow-x:auto}#jobs-table{font-size:11px}#jobs-table th,#jobs-table td{padding:2px 4px}\n"
    "#jobs-table td.num,#jobs-table td.status{white-space:nowrap}#jobs-table td.job{min-width:16em}\n"
    "#jobs-table .settings{color:#666;font-size:10px}\n"
    "#jobs-table td.job-error,#jobs-table td.image-error{color:#a00;white-space:pre-wrap;font-family:monospace}\n"
    "tr.failed td{background:#fff3f3}tr.pending td,tr.running td{color:#888}\n"
    "#image-grid td{vertical-align:top}#image-grid figcaption{font-size:12px;color:#444}\n"
    "img.frame-image{border:1px solid #ccc;display:block}\n"
    "div.missing-image{border:1px dashed #c66;color:#a00;font-size:12px;display:flex;align-items:center;"
    "justify-content:center;text-align:center}\n"
    "#plots{display:flex;flex-wrap:wrap;gap:1.5em}\n";

void write_summary(std::ostringstream& html, const fs::path& sweep_dir, const SweepIndex& index,
                   const std::vector<JobResult>& results) {
  size_t counts[4] = {};
  for (const JobResult& r : results) ++counts[size_t(r.job.status)];
  html << "<h1>avsm-sweep report</h1>\n<p class=\"note\" id=\"sweep-summary\">" << escape_markup(sweep_dir.string())
       << " \u2013 manifest " << escape_markup(index.manifest) << "<br>" << results.size()
       << " jobs: " << counts[size_t(JobStatus::done)] << " done, " << counts[size_t(JobStatus::failed)] << " failed, "
       << counts[size_t(JobStatus::pending)] + counts[size_t(JobStatus::running)] << " not finished.</p>\n";
}

void write_jobs_table(std::ostringstream& html, const std::vector<JobResult>& results) {
  const size_t figure_columns = capture::kPassStageCount + 2 + 3 + 4;
  html << "<section>\n<h2>Jobs</h2>\n<p class=\"note\">GPU ms: medians over the measured frames, each stage "
          "its passes summed; shadow = capture + sort + resolve / build + mips; other: the rest, with the error "
          "measurement of a job that compared to uncompressed (in its frame time too). Maps: every light's "
          "persistent maps; build: the capture lists (or the fixed build's depth image and hair bins); transients: "
          "the frame graph's aliased memory. |\u0394T|: transmittance error against uncompressed at the receivers "
          "the camera sees, all lights together (jobs with compare_to uncompressed). PSNR and MAE: frame.exr "
          "(RGB mapped by x / (1 + x)) against the reference job's.</p>\n"
       << "<div class=\"wide\"><table id=\"jobs-table\">\n<thead>\n<tr class=\"group\"><th colspan=\"4\">job</th>"
       << "<th colspan=\"" << capture::kPassStageCount + 2
       << "\">GPU ms</th><th colspan=\"3\">memory</th><th colspan=\"4\">error</th></tr>\n"
       << "<tr><th>id and settings</th><th>scene</th><th>technique</th><th>status</th>";
  for (capture::PassStage stage : capture::kPassStages)
    html << "<th class=\"num\">" << escape_markup(to_string(stage)) << "</th>";
  html << "<th class=\"num\">shadow</th><th class=\"num\">frame</th><th class=\"num\">maps</th>"
          "<th class=\"num\">build</th><th class=\"num\">transients</th><th class=\"num\">mean |\u0394T|</th>"
          "<th class=\"num\">max |\u0394T|</th><th class=\"num\">PSNR</th><th class=\"num\">MAE</th></tr>\n"
          "</thead>\n<tbody>\n";
  for (const JobResult& r : results) {
    const JobSettings& s = r.job.settings;
    html << "<tr class=\"job " << to_string(r.job.status) << "\" data-job=\"" << escape_markup(r.job.id)
         << "\"><td class=\"job\">" << escape_markup(r.job.id) << "<br><span class=\"settings\">"
         << escape_markup(settings_text(s)) << "</span></td><td title=\"" << escape_markup(s.scene) << "\">"
         << escape_markup(scene_name(s)) << "</td><td>" << escape_markup(r.technique) << "</td><td class=\"status\">"
         << escape_markup(status_text(r.job)) << "</td>";
    if (!r.frame) {
      const std::string why = r.job.status == JobStatus::failed
                                  ? (r.job.error.empty() ? "no error recorded" : r.job.error)
                                  : (r.job.status == JobStatus::done ? r.problem : "not finished");
      html << "<td class=\"job-error\" colspan=\"" << figure_columns << "\">" << escape_markup(why) << "</td></tr>\n";
      continue;
    }
    for (double ms : r.stage_ms) html << number_cell(format_value("%.3f", ms));
    html << number_cell(format_value("%.3f", capture::shadow_gpu_ms(r.stage_ms)))
         << number_cell(format_value("%.3f", r.frame->timings.frame_gpu_ms.median))
         << bytes_cell(map_bytes(r.frame->memory)) << bytes_cell(build_bytes(r.frame->memory))
         << bytes_cell(r.frame->memory.transient_bytes_aliased);
    if (r.shadow_error && r.shadow_error->receivers)
      html << number_cell(format_value("%.4f", r.shadow_error->mean()),
                          std::to_string(r.shadow_error->receivers) + " receivers")
           << number_cell(format_value("%.4f", r.shadow_error->max));
    else
      html << number_cell(kNoValue, "no quality.json (compare_to is not uncompressed)") << number_cell(kNoValue);
    if (r.image_error)
      html << number_cell(psnr_text(r.image_error->psnr_db), "against " + s.reference_job)
           << number_cell(format_value("%.5f", r.image_error->mean_abs_error), "against " + s.reference_job);
    else if (!r.image_error_problem.empty())  // the reason where the figures would be
      html << "<td class=\"image-error\" colspan=\"2\">" << escape_markup(r.image_error_problem) << "</td>";
    else
      html << number_cell(kNoValue, "no reference job") << number_cell(kNoValue, "no reference job");
    html << "</tr>\n";
  }
  html << "</tbody>\n</table></div>\n</section>\n";
}

// The job's frame.png at `scale` CSS pixels per pixel, or a box of the frame's size
// saying why there is none.
void write_frame_figure(std::ostringstream& html, const fs::path& sweep_dir, const JobResult& r, double scale) {
  std::string missing = r.frame ? "" : r.problem.empty() ? std::string(to_string(r.job.status)) : "unreadable";
  html << "<figure>";
  if (r.frame) {
    try {
      const capture::PngImage png = capture::embed_png(sweep_dir / r.job.output / "frame.png");
      html << "<img class=\"frame-image\" data-job=\"" << escape_markup(r.job.id) << "\" alt=\""
           << escape_markup(r.job.id) << "\" style=\"width:" << svg_number(png.width * scale)
           << "px;height:" << svg_number(png.height * scale) << "px\" src=\"" << png.data_uri << "\">";
    } catch (const std::exception& e) {
      missing = e.what();
    }
  }
  if (!missing.empty())
    html << "<div class=\"missing-image\" data-job=\"" << escape_markup(r.job.id)
         << "\" style=\"width:" << svg_number(r.job.settings.width * scale)
         << "px;height:" << svg_number(r.job.settings.height * scale) << "px\">" << escape_markup(missing) << "</div>";
  html << "<figcaption>" << escape_markup(r.job.id) << "</figcaption></figure>";
}

// A row per scene, a column per technique label (first appearances in manifest order),
// every frame at one scale: the widest frame as wide as a column can be for the columns
// to fit the page (160 to 320 CSS pixels; more columns scroll).
void write_images(std::ostringstream& html, const fs::path& sweep_dir, const std::vector<JobResult>& results) {
  std::vector<std::string> scenes, techniques;
  uint32_t widest = 0;
  for (const JobResult& r : results) {
    add_unique(scenes, scene_name(r.job.settings));
    add_unique(techniques, r.technique);
    widest = std::max(widest, r.job.settings.width);
  }
  const double column_width = std::clamp(1100.0 / double(std::max<size_t>(techniques.size(), 1)) - 16, 160.0, 320.0);
  const double scale = widest ? column_width / widest : 1.0;
  html << "<section>\n<h2>Frames</h2>\n<p class=\"note\">frame.png of every job at one scale ("
       << format_value("%.3g", scale) << " CSS pixels per pixel): a row per scene, a column per technique.</p>\n"
       << "<div class=\"wide\"><table id=\"image-grid\">\n<tr><th></th>";
  for (const std::string& technique : techniques) html << "<th>" << escape_markup(technique) << "</th>";
  html << "</tr>\n";
  for (const std::string& scene : scenes) {
    html << "<tr><th>" << escape_markup(scene) << "</th>";
    for (const std::string& technique : techniques) {
      html << "<td>";
      for (const JobResult& r : results)
        if (scene_name(r.job.settings) == scene && r.technique == technique)
          write_frame_figure(html, sweep_dir, r, scale);
      html << "</td>";
    }
    html << "</tr>\n";
  }
  html << "</table></div>\n</section>\n";
}

struct Point {
  double x, y;
  std::string label, job;
  size_t series;
};

// Tableau 10: one colour per scene.
const char* series_colour(size_t series) {
  static const char* const kColours[] = {"#4e79a7", "#f28e2b", "#e15759", "#76b7b2", "#59a14f",
                                         "#edc948", "#b07aa1", "#ff9da7", "#9c755f", "#bab0ac"};
  return kColours[series % std::size(kColours)];
}

struct Box {
  double x, y, w, h;
  bool overlaps(const Box& o) const { return x < o.x + o.w && o.x < x + w && y < o.y + o.h && o.y < y + h; }
};

struct LabelPlace {
  double x, y;  // the text's anchor and baseline
  const char* anchor;
};

// Beside the point at (x, y): above right, below right, above left, below left, or a
// line higher on the right or left,
// whichever lies inside `area` and overlaps the fewest points and labels already placed
// (the first of equals); the label's box is then taken.
LabelPlace place_label(double x, double y, const std::string& label, const Box& area, std::vector<Box>& taken) {
  const double w = 7.0 * double(label.size()), h = 12;
  const LabelPlace places[] = {{x + 7, y - 6, "start"}, {x + 7, y + 15, "start"}, {x - 7, y - 6, "end"},
                               {x - 7, y + 15, "end"},  {x + 7, y - 20, "start"}, {x - 7, y - 20, "end"}};
  auto box_of = [&](const LabelPlace& place) {
    return Box{place.anchor[0] == 's' ? place.x : place.x - w, place.y - h + 2, w, h};
  };
  auto cost = [&](const Box& box) {
    const bool inside =
        box.x >= area.x && box.y >= area.y && box.x + box.w <= area.x + area.w && box.y + box.h <= area.y + area.h;
    return (inside ? 0 : 1000) +
           std::count_if(taken.begin(), taken.end(), [&](const Box& t) { return t.overlaps(box); });
  };
  const LabelPlace* best = &places[0];
  for (const LabelPlace& place : places)
    if (cost(box_of(place)) < cost(box_of(*best))) best = &place;
  taken.push_back(box_of(*best));
  return *best;
}

// A scatter of `points` from 0 up on both axes, with a legend of `series`.
void write_scatter(std::ostringstream& html, const std::string& id, const std::string& x_label,
                   const std::vector<Point>& points, const std::vector<std::string>& series) {
  const double left = 64, right = 90, top = 16, plot_w = 440, plot_h = 300, bottom = 44;
  const double legend_h = 18.0 * double(series.size()) + 8;
  const double width = left + plot_w + right, height = top + plot_h + bottom + legend_h;
  double x_max = 0, y_max = 0;
  for (const Point& p : points) x_max = std::max(x_max, p.x), y_max = std::max(y_max, p.y);
  const double x_step = capture::nice_step(x_max, 5), y_step = capture::nice_step(y_max, 5);
  const double x_axis = x_max > 0 ? std::ceil(x_max / x_step - 1e-9) * x_step : x_step;
  const double y_axis = y_max > 0 ? std::ceil(y_max / y_step - 1e-9) * y_step : y_step;
  auto x_of = [&](double x) { return left + x / x_axis * plot_w; };
  auto y_of = [&](double y) { return top + plot_h - y / y_axis * plot_h; };

  html << "<svg id=\"" << id << "\" xmlns=\"http://www.w3.org/2000/svg\" width=\"" << svg_number(width)
       << "\" height=\"" << svg_number(height) << "\" viewBox=\"0 0 " << svg_number(width) << " " << svg_number(height)
       << "\" role=\"img\" aria-label=\"mean transmittance error against " << escape_markup(x_label) << "\">\n";
  const double epsilon = 1e-6;
  for (int k = 0; double(k) * x_step <= x_axis * (1 + epsilon); ++k) {
    const double x = x_of(double(k) * x_step);
    html << "<line x1=\"" << svg_number(x) << "\" y1=\"" << svg_number(top) << "\" x2=\"" << svg_number(x) << "\" y2=\""
         << svg_number(top + plot_h) << "\" stroke=\"#e3e3e3\"/><text x=\"" << svg_number(x) << "\" y=\""
         << svg_number(top + plot_h + 16) << "\" text-anchor=\"middle\" fill=\"#666\">"
         << format_value("%g", double(k) * x_step) << "</text>\n";
  }
  for (int k = 0; double(k) * y_step <= y_axis * (1 + epsilon); ++k) {
    const double y = y_of(double(k) * y_step);
    html << "<line x1=\"" << svg_number(left) << "\" y1=\"" << svg_number(y) << "\" x2=\"" << svg_number(left + plot_w)
         << "\" y2=\"" << svg_number(y) << "\" stroke=\"#e3e3e3\"/><text x=\"" << svg_number(left - 6) << "\" y=\""
         << svg_number(y + 4) << "\" text-anchor=\"end\" fill=\"#666\">" << format_value("%g", double(k) * y_step)
         << "</text>\n";
  }
  html << "<path d=\"M" << svg_number(left) << " " << svg_number(top) << "V" << svg_number(top + plot_h) << "H"
       << svg_number(left + plot_w) << "\" stroke=\"#333\" fill=\"none\"/>\n"
       << "<text x=\"" << svg_number(left + plot_w / 2) << "\" y=\"" << svg_number(top + plot_h + 36)
       << "\" text-anchor=\"middle\">" << escape_markup(x_label) << "</text>\n"
       << "<text transform=\"translate(14 " << svg_number(top + plot_h / 2)
       << ") rotate(-90)\" text-anchor=\"middle\">mean |\u0394T| against uncompressed</text>\n";
  std::vector<Box> taken;  // the points and the labels placed so far
  for (const Point& p : points) taken.push_back({x_of(p.x) - 5, y_of(p.y) - 5, 10, 10});
  for (const Point& p : points) {
    const double x = x_of(p.x), y = y_of(p.y);
    const LabelPlace place = place_label(x, y, p.label, {left, top - 12, plot_w + right, plot_h + 12}, taken);
    html << "<circle class=\"point\" data-job=\"" << escape_markup(p.job) << "\" cx=\"" << svg_number(x) << "\" cy=\""
         << svg_number(y) << "\" r=\"5\" fill=\"" << series_colour(p.series) << "\" fill-opacity=\"0.85\"><title>"
         << escape_markup(p.job + ": " + p.label + ", " + format_value("%.3f ms", p.x) + ", mean |\u0394T| " +
                          format_value("%.4f", p.y))
         << "</title></circle><text x=\"" << svg_number(place.x) << "\" y=\"" << svg_number(place.y)
         << "\" text-anchor=\"" << place.anchor << "\">" << escape_markup(p.label) << "</text>\n";
  }
  for (size_t s = 0; s < series.size(); ++s) {
    const double y = top + plot_h + bottom + 18.0 * double(s) + 8;
    html << "<circle cx=\"" << svg_number(left + 5) << "\" cy=\"" << svg_number(y - 4) << "\" r=\"5\" fill=\""
         << series_colour(s) << "\"/><text x=\"" << svg_number(left + 14) << "\" y=\"" << svg_number(y) << "\">"
         << escape_markup(series[s]) << "</text>\n";
  }
  if (points.empty())
    html << "<text x=\"" << svg_number(left + plot_w / 2) << "\" y=\"" << svg_number(top + plot_h / 2)
         << "\" text-anchor=\"middle\" fill=\"#a00\">no job measured its error</text>\n";
  html << "</svg>\n";
}

// The paper's trade-off: error against GPU cost, once against the shadow maps' own
// stages and once against the whole frame; a point per job with quality.json.
void write_tradeoff(std::ostringstream& html, const std::vector<JobResult>& results) {
  std::vector<std::string> scenes, unplotted;
  std::vector<Point> shadow_points, frame_points;
  for (const JobResult& r : results) {
    if (!r.frame || !r.shadow_error || !r.shadow_error->receivers) {
      unplotted.push_back(r.job.id +
                          (r.frame ? " (no quality.json)" : " (" + std::string(to_string(r.job.status)) + ")"));
      continue;
    }
    const std::string scene = scene_name(r.job.settings);
    add_unique(scenes, scene);
    const size_t series = size_t(std::find(scenes.begin(), scenes.end(), scene) - scenes.begin());
    const double error = r.shadow_error->mean();
    shadow_points.push_back({capture::shadow_gpu_ms(r.stage_ms), error, r.technique, r.job.id, series});
    frame_points.push_back({r.frame->timings.frame_gpu_ms.median, error, r.technique, r.job.id, series});
  }
  html << "<section>\n<h2>Error against cost</h2>\n<p class=\"note\">One point per job that compared to "
          "uncompressed, labelled with its technique, a colour per scene (the trade-off of the AVSM paper's "
          "Figure 10 and Table 1).</p>\n<div id=\"plots\">\n";
  write_scatter(html, "tradeoff-shadow", "shadow maps' GPU ms (capture + sort + resolve / build + mips)", shadow_points,
                scenes);
  write_scatter(html, "tradeoff-frame", "frame GPU ms", frame_points, scenes);
  html << "</div>\n";
  if (!unplotted.empty())
    html << "<p class=\"note\" id=\"unplotted\">Not plotted: " << escape_markup(joined(unplotted, "; ")) << ".</p>\n";
  html << "</section>\n";
}

}  // namespace

std::vector<JobResult> read_job_results(const fs::path& sweep_dir, const SweepIndex& index) {
  std::vector<JobResult> results;
  for (const JobRecord& job : index.jobs) results.push_back(read_job(sweep_dir, job));
  for (JobResult& result : results) compare_to_reference(sweep_dir, result, results);
  return results;
}

// The shots, merged from their chunks: frames rendered of the shot's, the chunks, and its
// first and last frames rendered so far.
void write_shots(std::ostringstream& html, const fs::path& sweep_dir, const std::vector<ShotIndex>& shots) {
  if (shots.empty()) return;
  html << "<section>\n<h2>Shots</h2>\n<table id=\"shots-table\">\n<tr><th>shot</th><th>frames</th><th>fps</th>"
          "<th>chunks</th><th>first and last frame rendered</th></tr>\n";
  for (const ShotIndex& shot : shots) {
    const int total = shot.last_frame - shot.first_frame + 1;
    html << "<tr><td>" << capture::escape_markup(shot.id) << "</td><td>" << shot.frames.size() << " of " << total << " ("
         << shot.first_frame << " to " << shot.last_frame << ")</td><td>" << capture::format_value("%g", shot.fps) << "</td><td>"
         << capture::escape_markup(joined(shot.chunks, ", ")) << "</td><td>";
    for (const ShotFrameIndex* frame : {shot.frames.empty() ? nullptr : &shot.frames.front(),
                                        shot.frames.size() < 2 ? nullptr : &shot.frames.back()}) {
      if (frame == nullptr) continue;
      std::error_code ec;
      if (!fs::exists(sweep_dir / frame->image, ec)) continue;
      html << "<img width=\"160\" alt=\"" << capture::escape_markup(shot.id) << " frame " << frame->frame << "\" src=\""
           << capture::embed_png(sweep_dir / frame->image).data_uri << "\"> ";
    }
    html << "</td></tr>\n";
  }
  html << "</table>\n</section>\n";
}

void write_sweep_report(const fs::path& sweep_dir, const fs::path& html_path) {
  const SweepIndex index = read_index(sweep_dir);
  const std::vector<JobResult> results = read_job_results(sweep_dir, index);
  std::ostringstream html;
  capture::write_html_head(html, "avsm-sweep report: " + sweep_dir.filename().string(), kStyle);
  write_summary(html, sweep_dir, index, results);
  write_jobs_table(html, results);
  write_shots(html, sweep_dir, index.shots);
  write_images(html, sweep_dir, results);
  write_tradeoff(html, results);
  html << "<footer>\n<p class=\"note\">Written by avsm-sweep report from "
       << escape_markup(index_file(sweep_dir).string())
       << " and the jobs' capture folders.</p>\n</footer>\n</body>\n</html>\n";
  capture::write_text(html_path, html.str());
}

}  // namespace avsm::sweep
