#include "sweep/compare.h"
#include <nlohmann/json.hpp>
#include <map>
#include <fstream>

#include <algorithm>
#include <charconv>
#include <cmath>
#include <cstdio>
#include <limits>
#include <stdexcept>

#include "capture/image_difference.h"
#include "io/image_io.h"
#include "sweep/sweep_index.h"

namespace avsm::sweep {
namespace fs = std::filesystem;

namespace {

std::string format(const char* pattern, double value) {
  char text[64];
  std::snprintf(text, sizeof text, pattern, value);
  return text;
}

std::string ms_text(double ms) { return format("%.3f ms", ms); }

std::string ratio_text(double ratio) { return std::isinf(ratio) ? "x inf" : format("x%.2f", ratio); }

std::string bytes_text(uint64_t bytes) {
  if (bytes < 1024) return std::to_string(bytes) + " B";
  if (bytes < 1024 * 1024) return format("%.1f KiB", double(bytes) / 1024.0);
  return format("%.2f MiB", double(bytes) / (1024.0 * 1024.0));
}

// NEW / BASE, where a figure that was 0 and grew is infinitely larger and 0 / 0 is 1.
double ratio_of(double base, double now) {
  if (base > 0) return now / base;
  return now > 0 ? std::numeric_limits<double>::infinity() : 1.0;
}

Check listed(std::string name, std::string base, std::string now, std::string message) {
  return {std::move(name), std::move(base), std::move(now), "", "", Verdict::listed, std::move(message)};
}

// ---- timings ----

// A pass is timed well enough to judge when, on either side, it took at least
// min_pass_ms and min_pass_share of the longer frame: below that a pass's time is
// mostly the timestamps' own jitter, which can make it read several times longer.
bool big_enough(double pass_ms, double frame_ms, const TimingThresholds& limits) {
  return pass_ms >= limits.min_pass_ms && pass_ms >= limits.min_pass_share * frame_ms;
}

Check pass_check(const capture::PassTiming& base, const capture::PassTiming& now, double frame_ms,
                 const TimingThresholds& limits) {
  const double ratio = ratio_of(base.gpu_ms.median, now.gpu_ms.median);
  Check check{"gpu_ms '" + base.name + "'", ms_text(base.gpu_ms.median), ms_text(now.gpu_ms.median),
              ratio_text(ratio), "<= " + ratio_text(limits.max_pass_ratio), Verdict::pass, ""};
  if (!big_enough(std::max(base.gpu_ms.median, now.gpu_ms.median), frame_ms, limits)) {
    check.verdict = Verdict::listed;
    check.message = format("too short to judge (< %g ms", limits.min_pass_ms) +
                    format(" or < %g%% of the frame)", 100.0 * limits.min_pass_share);
  } else if (ratio > limits.max_pass_ratio) {
    check.verdict = Verdict::fail;
    check.message = "pass '" + base.name + "' took " + ratio_text(ratio) + " its BASE time (limit " +
                    ratio_text(limits.max_pass_ratio) + ", timing.max_pass_ratio)";
  }
  return check;
}

const capture::PassTiming* find_pass(const capture::TimingReport& report, const std::string& name) {
  for (const capture::PassTiming& pass : report.passes)
    if (pass.name == name) return &pass;
  return nullptr;
}

Check frame_time_check(const capture::TimingReport& base, const capture::TimingReport& now,
                       const TimingThresholds& limits) {
  const double b = base.frame_gpu_ms.median, n = now.frame_gpu_ms.median;
  const double ratio = ratio_of(b, n);
  Check check{"frame gpu_ms", ms_text(b), ms_text(n), ratio_text(ratio), "<= " + ratio_text(limits.max_frame_ratio),
              Verdict::pass, ""};
  if (base.frames.empty() || now.frames.empty()) {
    check.verdict = Verdict::listed;
    check.message = "no measured frames on one side (capture with --frames 2 or more)";
  } else if (ratio > limits.max_frame_ratio) {
    check.verdict = Verdict::fail;
    check.message = "the frame took " + ratio_text(ratio) + " its BASE GPU time (limit " +
                    ratio_text(limits.max_frame_ratio) + ", timing.max_frame_ratio)";
  }
  return check;
}

// Lists the judged checks of a CPU device's times, ratios kept: its passes run on the
// cores the rest of the machine shares, so an unchanged frame moves by several times.
void unjudged_on_cpu_device(std::vector<Check>& checks) {
  for (Check& check : checks)
    if (check.verdict != Verdict::listed) {
      check.verdict = Verdict::listed;
      check.message = "not judged on a CPU device (timing.judge_cpu_devices)";
    }
}

// ---- memory ----

Check bytes_check(const std::string& name, uint64_t base, uint64_t now, const MemoryThresholds& limits) {
  const double ratio = ratio_of(double(base), double(now));
  Check check{name, bytes_text(base), bytes_text(now), ratio_text(ratio), "<= " + ratio_text(limits.max_ratio),
              Verdict::pass, ""};
  if (ratio > limits.max_ratio && now >= base + limits.min_increase_bytes) {
    check.verdict = Verdict::fail;
    check.message = name + " grew " + ratio_text(ratio) + " by " + bytes_text(now - base) + " (limit " +
                    ratio_text(limits.max_ratio) + ", memory.max_ratio, for increases of at least " +
                    bytes_text(limits.min_increase_bytes) + ", memory.min_increase_bytes)";
  }
  return check;
}

template <class Light>
const Light* find_light(const std::vector<Light>& lights, const std::string& name) {
  for (const Light& light : lights)
    if (light.light == name) return &light;
  return nullptr;
}

// Lights of `now` that `base` does not have, as listed checks.
template <class Light>
void list_new_lights(const std::vector<Light>& base, const std::vector<Light>& now, const std::string& what,
                     std::vector<Check>& checks) {
  for (const Light& light : now)
    if (!find_light(base, light.light)) checks.push_back(listed(what + " '" + light.light + "'", "-", "", "only in NEW"));
}

// ---- quality ----

std::string error_text(const capture::ErrorStats& stats) {
  return stats.receivers ? format("%.5f", stats.mean()) : std::string("no receivers");
}

Check quality_mean_check(const capture::LightQuality& base, const capture::LightQuality& now,
                         const QualityThresholds& limits) {
  const capture::ErrorStats b = base.all(), n = now.all();
  const double increase = n.mean() - b.mean();
  Check check{"quality '" + base.light + "' mean_abs_error", error_text(b), error_text(n), format("%+.5f", increase),
              format("<= +%g", limits.max_mean_abs_error_increase), Verdict::pass, ""};
  if (increase > limits.max_mean_abs_error_increase) {
    check.verdict = Verdict::fail;
    check.message = "light '" + base.light + "': the mean shadow error against the exact reference rose by " +
                    format("%.5f", increase) + format(" (limit %g, quality.max_mean_abs_error_increase)",
                                                      limits.max_mean_abs_error_increase);
  }
  return check;
}

// The max follows single texels: reported, not judged.
Check quality_max_check(const capture::LightQuality& base, const capture::LightQuality& now) {
  const capture::ErrorStats b = base.all(), n = now.all();
  return {"quality '" + base.light + "' max_abs_error", format("%.5f", b.max), format("%.5f", n.max),
          format("%+.5f", n.max - b.max), "", Verdict::listed, "reported, not judged (one texel can move it)"};
}

// ---- settings ----

// One setting as the gate shows it: its key ("width", "volume_shading.mode", "nodes") and value.
using Setting = std::pair<std::string, std::string>;

// A capture's settings: the frame's, then each light's (by name).
struct SettingList {
  std::vector<Setting> frame;
  std::vector<std::pair<std::string, std::vector<Setting>>> lights;
};

// The shortest text that reads back as the same number: settings that differ at all show
// different values, and a float setting shows as written (0.1, not 0.100000001).
template <class Number>
std::string number_text(Number value) {
  char text[64];
  const auto [end, error] = std::to_chars(text, text + sizeof text, value);
  return error == std::errc() ? std::string(text, end) : format("%g", double(value));
}
std::string bool_text(bool value) { return value ? "true" : "false"; }

SettingList settings_of(const capture::SettingsReport& s) {
  std::string plots;
  for (const std::string& plot : s.plot_texels) plots += (plots.empty() ? "" : " ") + plot;
  SettingList list;
  list.frame = {{"scene", s.scene},
                {"camera", s.camera},
                {"width", std::to_string(s.width)},
                {"height", std::to_string(s.height)},
                {"frames", std::to_string(s.frames)},
                {"frames_in_flight", std::to_string(s.frames_in_flight)},
                {"orbit_degrees", number_text(s.orbit_degrees)},
                {"light_orbit_degrees", number_text(s.light_orbit_degrees)},
                {"validation", bool_text(s.validation)},
                {"volume_shading.mode", scene::to_string(s.volume_shading.mode)},
                {"volume_shading.resolution_divisor", std::to_string(s.volume_shading.resolution_divisor)},
                {"volume_shading.step_voxels", number_text(s.volume_shading.step_voxels)},
                {"compare_volume_shading", bool_text(s.compare_volume_shading)},
                {"exponential_interpolation", bool_text(s.exponential_interpolation)},
                {"compare_to_uncompressed", bool_text(s.compare_to_uncompressed)},
                {"probe_points", std::to_string(s.probe_points)},
                {"plot_texels", plots.empty() ? "none" : plots},
                {"shadows.budget_mib", number_text(s.shadows.budget_mib)},
                {"shadows.fit_budget", bool_text(s.shadows.fit_budget)},
                {"shadows.clusters", std::to_string(s.shadows.clusters)}};
  for (const capture::LightSettings& light : s.lights) {
    const scene::ShadowSettings& shadow = light.shadow;
    std::vector<Setting> settings{{"type", std::string(scene::to_string(light.type))},
                                  {"technique", shadow.technique},
                                  {"nodes", std::to_string(shadow.nodes)},
                                  {"resolution", std::to_string(shadow.resolution)},
                                  {"lowered_to", std::to_string(light.lowered_to)},
                                  {"filter", std::string(scene::to_string(shadow.filter))},
                                  {"kernel", std::string(scene::to_string(shadow.kernel))},
                                  {"kernel_radius", std::to_string(shadow.kernel_radius)},
                                  {"sort", bool_text(shadow.sort)},
                                  {"build", std::string(scene::to_string(shadow.build))},
                                  {"fit", std::string(scene::to_string(shadow.fit))},
                                  {"distance", number_text(shadow.distance)},
                                  {"cascades", std::to_string(shadow.cascades)},
                                  {"cascade_blend", number_text(shadow.cascade_blend)},
                                  {"clusters", std::to_string(shadow.clusters)},
                                  {"layout", std::string(scene::to_string(shadow.layout))}};
    if (shadow.layout == scene::ShadowLayout::paged)
      settings.insert(settings.end(), {{"virtual_resolution", std::to_string(shadow.virtual_resolution)},
                                       {"page_size", std::to_string(shadow.page_size)},
                                       {"page_pool_mib", number_text(shadow.page_pool_mib)},
                                       {"page_lod_bias", number_text(shadow.page_lod_bias)},
                                       {"page_volume_lod_bias", number_text(shadow.page_volume_lod_bias)}});
    for (const auto& [name, value] : shadow.parameters) settings.push_back({"parameters." + name, number_text(value)});
    list.lights.push_back({light.light, std::move(settings)});
  }
  return list;
}

// What a capture folder without settings.json still records: the image size
// (timings.json) and per light what memory.json holds of its settings.
SettingList recorded_settings_of(const capture::FrameReport& report) {
  SettingList list;
  list.frame = {{"width", std::to_string(report.timings.width)}, {"height", std::to_string(report.timings.height)}};
  for (const passes::LightShadowStats& light : report.memory.lights)
    list.lights.push_back({light.light,
                           {{"technique", light.technique},
                            {"nodes", std::to_string(light.nodes)},
                            {"resolution", std::to_string(light.resolution)},
                            {"map_kind", light.map_kind},
                            {"build", light.fixed_build ? "fixed" : "lists"}}});
  return list;
}

const std::string kAbsent = "-";

// Failed unless allowed, then listed: one setting that differs. `difference` says how
// ("is 8 in BASE but 4 in NEW").
Check setting_check(const std::string& key, const std::string& base, const std::string& now,
                    const std::string& difference, const CompareOptions& options) {
  Check check{"setting " + key, base, now, "", "equal", Verdict::fail, ""};
  if (options.allow_different_settings) {
    check.verdict = Verdict::listed;
    check.message = "differs (allowed by --allow-different-settings)";
  } else {
    check.message = check.name + " " + difference +
                    ": the figures compare different settings (--allow-different-settings compares them anyway)";
  }
  return check;
}

Check setting_check(const std::string& key, const std::string& base, const std::string& now,
                    const CompareOptions& options) {
  const std::string difference = base == kAbsent ? "is only in NEW (" + now + ")"
                                 : now == kAbsent ? "is only in BASE (" + base + ")"
                                                  : "is " + base + " in BASE but " + now + " in NEW";
  return setting_check(key, base, now, difference, options);
}

const std::string* find_setting(const std::vector<Setting>& settings, const std::string& key) {
  for (const Setting& setting : settings)
    if (setting.first == key) return &setting.second;
  return nullptr;
}

// A check per key whose value differs or that one side lacks; keys named `prefix` + key.
void compare_setting_lists(const std::vector<Setting>& base, const std::vector<Setting>& now, const std::string& prefix,
                           const CompareOptions& options, std::vector<Check>& checks) {
  for (const auto& [key, value] : base) {
    const std::string* other = find_setting(now, key);
    if (!other || *other != value) checks.push_back(setting_check(prefix + key, value, other ? *other : kAbsent, options));
  }
  for (const auto& [key, value] : now)
    if (!find_setting(base, key)) checks.push_back(setting_check(prefix + key, kAbsent, value, options));
}

const std::vector<Setting>* find_light_settings(const SettingList& list, const std::string& light) {
  for (const auto& [name, settings] : list.lights)
    if (name == light) return &settings;
  return nullptr;
}

size_t setting_count(const SettingList& list) {
  size_t count = list.frame.size();
  for (const auto& light : list.lights) count += light.second.size();
  return count;
}

// ---- folders ----

enum class FolderKind { capture, sweep };

FolderKind folder_kind(const fs::path& dir, const char* side) {
  std::error_code ec;
  if (!fs::is_directory(dir, ec))
    throw std::runtime_error(dir.string() + ": no such folder (" + side + ": a capture folder or a sweep folder)");
  if (fs::is_regular_file(index_file(dir), ec)) return FolderKind::sweep;
  if (fs::is_regular_file(dir / "timings.json", ec)) return FolderKind::capture;
  throw std::runtime_error(dir.string() + ": neither a sweep folder (index.json) nor a capture folder (timings.json)");
}

const char* kind_name(FolderKind kind) { return kind == FolderKind::sweep ? "a sweep folder" : "a capture folder"; }

// The one check of a job that cannot be compared: failed when NEW lost a job BASE had done.
SuiteResult job_not_compared(const JobRecord* base, const JobRecord* now) {
  const std::string id = base ? base->id : now->id;
  const auto status = [](const JobRecord* job) { return job ? std::string(to_string(job->status)) : "-"; };
  Check check{"job", status(base), status(now), "", "done", Verdict::listed, ""};
  if (!now) {
    check.message = "only in BASE";
  } else if (!base) {
    check.message = "only in NEW";
  } else if (base->status != JobStatus::done) {
    check.message = "not done in BASE: nothing to compare against";
  } else {
    check.verdict = Verdict::fail;
    check.message = "job '" + id + "' was done in BASE but is " + std::string(to_string(now->status)) + " in NEW" +
                    (now->error.empty() ? "" : ": " + now->error);
  }
  return {id, {check}};
}

Check settings_changed(const JobRecord& base, const JobRecord& now) {
  const auto joined = [](const std::vector<std::string>& args) {
    std::string text;
    for (const std::string& arg : args) text += (text.empty() ? "" : " ") + arg;
    return text;
  };
  return listed("capture arguments", joined(base.capture_args), joined(now.capture_args),
                "differ: the figures compare different settings");
}

GateResult compare_sweeps(const fs::path& base, const fs::path& now, const Thresholds& limits,
                          const CompareOptions& options) {
  const SweepIndex b = read_index(base), n = read_index(now);
  GateResult result{base.string(), now.string(), {}};
  for (const JobRecord& job : b.jobs) {
    const JobRecord* other = n.find(job.id);
    if (other && job.status == JobStatus::done && other->status == JobStatus::done) {
      result.suites.push_back(compare_captures(job.id, base / job.output, now / other->output, limits, options));
      if (job.capture_args != other->capture_args)  // the manifest changed the job: say so first
        result.suites.back().checks.insert(result.suites.back().checks.begin(), settings_changed(job, *other));
    } else
      result.suites.push_back(job_not_compared(&job, other));
  }
  for (const JobRecord& job : n.jobs)
    if (!b.find(job.id)) result.suites.push_back(job_not_compared(nullptr, &job));
  return result;
}

}  // namespace

size_t SuiteResult::failures() const {
  return size_t(std::count_if(checks.begin(), checks.end(), [](const Check& c) { return c.verdict == Verdict::fail; }));
}

size_t GateResult::failures() const {
  size_t total = 0;
  for (const SuiteResult& suite : suites) total += suite.failures();
  return total;
}

std::vector<Check> compare_timings(const capture::TimingReport& base, const capture::TimingReport& now,
                                   const TimingThresholds& limits) {
  std::vector<Check> checks{frame_time_check(base, now, limits)};
  const double frame_ms = std::max(base.frame_gpu_ms.median, now.frame_gpu_ms.median);
  for (const capture::PassTiming& pass : base.passes) {
    if (const capture::PassTiming* other = find_pass(now, pass.name))
      checks.push_back(pass_check(pass, *other, frame_ms, limits));
    else
      checks.push_back(listed("gpu_ms '" + pass.name + "'", ms_text(pass.gpu_ms.median), "-", "only in BASE"));
  }
  for (const capture::PassTiming& pass : now.passes)
    if (!find_pass(base, pass.name))
      checks.push_back(listed("gpu_ms '" + pass.name + "'", "-", ms_text(pass.gpu_ms.median), "only in NEW"));
  if ((base.cpu_device || now.cpu_device) && !limits.judge_cpu_devices)
    unjudged_on_cpu_device(checks);
  return checks;
}

std::vector<Check> compare_quality(const std::optional<capture::QualityReport>& base,
                                   const std::optional<capture::QualityReport>& now,
                                   const QualityThresholds& limits) {
  if (!base && !now) return {};
  if (!base || !now)
    return {listed("quality.json", base ? "yes" : "-", now ? "yes" : "-",
                   std::string("only in ") + (base ? "BASE" : "NEW") + " (capture both with --compare-to uncompressed)")};
  std::vector<Check> checks;
  for (const capture::LightQuality& light : base->lights) {
    const capture::LightQuality* other = find_light(now->lights, light.light);
    if (!other) {
      checks.push_back(listed("quality '" + light.light + "'", error_text(light.all()), "-", "only in BASE"));
      continue;
    }
    checks.push_back(quality_mean_check(light, *other, limits));
    checks.push_back(quality_max_check(light, *other));
  }
  list_new_lights(base->lights, now->lights, "quality", checks);
  return checks;
}

std::vector<Check> compare_memory(const capture::MemoryReport& base, const capture::MemoryReport& now,
                                  const MemoryThresholds& limits) {
  std::vector<Check> checks{
      bytes_check("memory transient_bytes_aliased", base.transient_bytes_aliased, now.transient_bytes_aliased, limits)};
  for (const passes::LightShadowStats& light : base.lights) {
    const std::string prefix = "memory '" + light.light + "' ";
    const passes::LightShadowStats* other = find_light(now.lights, light.light);
    if (!other) {
      checks.push_back(listed(prefix + "map_bytes", bytes_text(light.map_bytes), "-", "only in BASE"));
      continue;
    }
    checks.push_back(bytes_check(prefix + "map_bytes", light.map_bytes, other->map_bytes, limits));
    checks.push_back(bytes_check(prefix + "capture_bytes", light.capture_bytes, other->capture_bytes, limits));
  }
  list_new_lights(base.lights, now.lights, "memory", checks);
  return checks;
}

std::vector<Check> compare_settings(const capture::FrameReport& base, const capture::FrameReport& now,
                                    const CompareOptions& options) {
  std::vector<Check> checks;
  const bool recorded = base.settings && now.settings;
  if (!recorded) {
    const std::string side = !base.settings && !now.settings ? "BASE and NEW" : !base.settings ? "BASE" : "NEW";
    checks.push_back(listed("settings.json", base.settings ? "yes" : kAbsent, now.settings ? "yes" : kAbsent,
                            "missing in " + side + " (captured before it was written): only the image size and each "
                            "light's technique, nodes, resolution, map_kind and build (timings.json, memory.json) "
                            "are compared"));
  }
  const SettingList b = recorded ? settings_of(*base.settings) : recorded_settings_of(base);
  const SettingList n = recorded ? settings_of(*now.settings) : recorded_settings_of(now);
  const size_t before = checks.size();
  compare_setting_lists(b.frame, n.frame, "", options, checks);
  for (const auto& [light, settings] : b.lights) {
    const std::string prefix = "'light " + light + "'";
    if (const std::vector<Setting>* other = find_light_settings(n, light))
      compare_setting_lists(settings, *other, prefix + " ", options, checks);
    else
      checks.push_back(setting_check(prefix, "yes", kAbsent, "is only in BASE", options));
  }
  for (const auto& [light, settings] : n.lights)
    if (!find_light_settings(b, light))
      checks.push_back(setting_check("'light " + light + "'", kAbsent, "yes", "is only in NEW", options));
  if (checks.size() == before)  // nothing differs: one check says how much was compared
    checks.push_back({"settings", std::to_string(setting_count(b)) + " settings",
                      std::to_string(setting_count(n)) + " settings", "", "equal", Verdict::pass, ""});
  return checks;
}

std::vector<Check> compare_images(const gpu::ImageRGBA32F& base, const gpu::ImageRGBA32F& now,
                                  const ImageThresholds& limits) {
  const auto size = [](const gpu::ImageRGBA32F& image) {
    return std::to_string(image.width) + "x" + std::to_string(image.height);
  };
  if (base.width != now.width || base.height != now.height)
    return {{"image size", size(base), size(now), "", "equal", Verdict::fail,
             "frame.exr is " + size(base) + " in BASE but " + size(now) +
                 " in NEW: compare captures made with the same --width and --height"}};
  const capture::ImageDifference d = capture::image_difference(now, base);
  Check psnr{"image psnr", "", "", std::isinf(d.psnr_db) ? "inf (equal)" : format("%.2f dB", d.psnr_db),
             format(">= %g dB", limits.min_psnr_db), Verdict::pass, ""};
  if (d.psnr_db < limits.min_psnr_db) {
    psnr.verdict = Verdict::fail;
    psnr.message = "frame.exr differs from BASE: PSNR " + format("%.2f dB", d.psnr_db) +
                   format(" (limit %g dB, image.min_psnr_db)", limits.min_psnr_db);
  }
  Check mae{"image mean_abs_error", "", "", format("%.5f", d.mean_abs_error),
            format("<= %g", limits.max_mean_abs_error), Verdict::pass, ""};
  if (d.mean_abs_error > limits.max_mean_abs_error) {
    mae.verdict = Verdict::fail;
    mae.message = "frame.exr differs from BASE: mean absolute error " + format("%.5f", d.mean_abs_error) +
                  format(" (limit %g, image.max_mean_abs_error)", limits.max_mean_abs_error);
  }
  return {psnr, mae};
}

namespace {

// A shot's frames as shot.json lists them: frame number -> image (relative to the folder).
std::map<int, fs::path> shot_frames(const fs::path& dir) {
  const fs::path file = dir / "shot.json";
  std::ifstream in(file);
  std::map<int, fs::path> frames;
  try {
    const nlohmann::json shot = nlohmann::json::parse(in);
    for (const nlohmann::json& frame : shot.at("frames"))
      frames[frame.at("frame").get<int>()] = frame.at("image").get<std::string>();
  } catch (const std::exception& error) {
    throw std::runtime_error(file.string() + ": not a shot.json avsm-capture writes (" + error.what() + ")");
  }
  return frames;
}

std::string frame_list(const std::vector<int>& frames) {
  std::string text;
  for (size_t i = 0; i < frames.size() && i < 8; ++i) text += (i ? ", " : "") + std::to_string(frames[i]);
  return frames.size() > 8 ? text + ", ... (" + std::to_string(frames.size()) + " frames)" : text;
}

}  // namespace

std::vector<Check> compare_shots(const fs::path& base, const fs::path& now, const ImageThresholds& limits) {
  const bool base_shot = fs::exists(base / "shot.json"), now_shot = fs::exists(now / "shot.json");
  if (!base_shot && !now_shot) return {};
  if (base_shot != now_shot)
    return {{"shot", base_shot ? "shot" : "-", now_shot ? "shot" : "-", "", "both", Verdict::fail,
             std::string(base_shot ? "NEW" : "BASE") + " holds no shot.json: compare shots with shots (--frame-range)"}};
  const std::map<int, fs::path> b = shot_frames(base), n = shot_frames(now);
  std::vector<int> missing, extra;
  for (const auto& [frame, image] : b)
    if (!n.count(frame)) missing.push_back(frame);
  for (const auto& [frame, image] : n)
    if (!b.count(frame)) extra.push_back(frame);
  std::vector<Check> checks;
  Check count{"shot frames", std::to_string(b.size()), std::to_string(n.size()), "", "BASE's frames", Verdict::pass, ""};
  if (!missing.empty()) {
    count.verdict = Verdict::fail;
    count.message = "NEW lacks frames " + frame_list(missing) + " of BASE's shot";
  } else if (!extra.empty()) {
    count.verdict = Verdict::listed;
    count.message = "frames only NEW has, not compared: " + frame_list(extra);
  }
  checks.push_back(count);

  struct Worst {
    int frame = -1;
    capture::ImageDifference difference{0.0, std::numeric_limits<double>::infinity()};
  } worst_psnr, worst_error;
  for (const auto& [frame, image] : b) {
    if (!n.count(frame)) continue;
    const gpu::ImageRGBA32F before = io::read_png(base / image), after = io::read_png(now / n.at(frame));
    if (before.width != after.width || before.height != after.height) {
      checks.push_back({"shot frame size", std::to_string(before.width) + "x" + std::to_string(before.height),
                        std::to_string(after.width) + "x" + std::to_string(after.height), "", "equal", Verdict::fail,
                        "frame " + std::to_string(frame) + " differs in size: compare shots made with the same --width and --height"});
      return checks;
    }
    const capture::ImageDifference d = capture::image_difference(after, before);
    if (worst_psnr.frame < 0 || d.psnr_db < worst_psnr.difference.psnr_db) worst_psnr = {frame, d};
    if (worst_error.frame < 0 || d.mean_abs_error > worst_error.difference.mean_abs_error) worst_error = {frame, d};
  }
  if (worst_psnr.frame < 0) return checks;
  const double psnr = worst_psnr.difference.psnr_db, error = worst_error.difference.mean_abs_error;
  Check psnr_check{"shot worst psnr (frame " + std::to_string(worst_psnr.frame) + ")", "", "",
                   std::isinf(psnr) ? "inf (equal)" : format("%.2f dB", psnr), format(">= %g dB", limits.min_psnr_db),
                   Verdict::pass, ""};
  if (psnr < limits.min_psnr_db) {
    psnr_check.verdict = Verdict::fail;
    psnr_check.message = "shot frame " + std::to_string(worst_psnr.frame) + " differs from BASE's most: PSNR " +
                         format("%.2f dB", psnr) + format(" (limit %g dB, image.min_psnr_db)", limits.min_psnr_db);
  }
  Check error_check{"shot worst mean_abs_error (frame " + std::to_string(worst_error.frame) + ")", "", "",
                    format("%.5f", error), format("<= %g", limits.max_mean_abs_error), Verdict::pass, ""};
  if (error > limits.max_mean_abs_error) {
    error_check.verdict = Verdict::fail;
    error_check.message = "shot frame " + std::to_string(worst_error.frame) + " differs from BASE's most: mean absolute error " +
                          format("%.5f", error) + format(" (limit %g, image.max_mean_abs_error)", limits.max_mean_abs_error);
  }
  checks.push_back(psnr_check);
  checks.push_back(error_check);
  return checks;
}

SuiteResult compare_captures(const std::string& name, const fs::path& base, const fs::path& now,
                             const Thresholds& limits, const CompareOptions& options) {
  const capture::FrameReport b = capture::read_frame_report(base), n = capture::read_frame_report(now);
  SuiteResult suite{name, compare_settings(b, n, options)};
  for (std::vector<Check> part : {compare_images(io::read_exr(base / "frame.exr"), io::read_exr(now / "frame.exr"), limits.image),
                                  compare_timings(b.timings, n.timings, limits.timing),
                                  compare_quality(b.quality, n.quality, limits.quality),
                                  compare_memory(b.memory, n.memory, limits.memory),
                                  compare_shots(base, now, limits.image)})
    suite.checks.insert(suite.checks.end(), part.begin(), part.end());
  return suite;
}


GateResult compare_folders(const fs::path& base, const fs::path& now, const Thresholds& limits,
                           const CompareOptions& options) {
  const FolderKind kind = folder_kind(base, "BASE");
  if (folder_kind(now, "NEW") != kind)
    throw std::runtime_error("BASE " + base.string() + " is " + kind_name(kind) + " but NEW " + now.string() +
                             " is not: compare captures with captures, sweeps with sweeps");
  if (kind == FolderKind::sweep) return compare_sweeps(base, now, limits, options);
  return {base.string(), now.string(), {compare_captures("capture", base, now, limits, options)}};
}

}  // namespace avsm::sweep
