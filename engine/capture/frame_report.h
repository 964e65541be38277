#pragma once
// One typed report of a captured frame: what timings.json, memory.json,
// settings.json, quality.json and probes.json hold, what report.html shows (capture/report.h) and
// what the viewer's panel reads. Each file's keys are spelled once, in
// frame_report.cpp: its to_json (the file's only writer) and its from_json (for a
// tool that reads a capture folder back, read_frame_report()). nlohmann::json
// objects keep their keys sorted, so a file's bytes do not depend on the order of
// the fields here.
#include <nlohmann/json_fwd.hpp>
#include <rendergraph/plan.h>

#include <cstdint>
#include <filesystem>
#include <map>
#include <optional>
#include <string>
#include <vector>

#include "capture/quality.h"
#include "capture/shot.h"
#include "capture/resolution.h"
#include "passes/shadows/shadow_stats.h"
#include "scene/bounds.h"
#include "scene/light.h"
#include "scene/volume.h"

namespace avsm::capture {

class FrameTimingLog;

// ---- timings.json ----

// Of one figure over the measured frames.
struct Spread {
  double min = 0, median = 0, max = 0;
  bool operator==(const Spread&) const = default;
};
Spread spread_of(std::vector<double> values);  // all 0 when empty

struct PassTiming {
  std::string name;
  rg::QueueType queue = rg::QueueType::Graphics;
  Spread gpu_ms, cpu_record_ms;
  bool operator==(const PassTiming&) const = default;
};

struct FrameSample {
  double gpu_ms = 0;          // the passes' GPU times summed
  double wall_ms = 0;         // build, record, submit and wait
  double submit_wall_ms = 0;  // submit to completion on the CPU clock
  double shadow_gpu_ms = 0;   // the shadow maps' passes (capture, sort, build, mips: pass_stages.h)
  double inspection_gpu_ms = 0;  // passes that only show or measure the frame (is_inspection_pass())
  uint32_t pages_built = 0;   // paged maps' pages built, every light's summed
  uint32_t pages_pending = 0;  // pages the receivers asked for that coarser levels stood in for
  // The shadow passes' ms by step (shadow_step(): "capture opaque", "capture hair",
  // "capture smoke", "sort", "resolve / build", "mips", ...), every light's summed.
  std::map<std::string, double> shadow_step_gpu_ms;
  bool operator==(const FrameSample&) const = default;
};

struct TimingReport {
  std::string device, driver, timestamp_mode;
  // A CPU implementation (lavapipe): its "GPU" times are CPU time on cores the rest of
  // the machine shares, so they measure the machine's load as much as the frame.
  // False in reports written before it was recorded.
  bool cpu_device = false;
  uint32_t width = 0, height = 0;
  std::vector<PassTiming> passes;  // in the order first recorded
  Spread frame_gpu_ms, frame_wall_ms, frame_submit_wall_ms;
  std::vector<FrameSample> frames;  // one per measured frame

  // Each pass's median over the measured frames; nullopt for a pass never timed.
  std::optional<double> median_gpu_ms(const std::string& pass) const;
  bool operator==(const TimingReport&) const = default;
};

// The passes, frame spreads and samples of `log`'s measured frames; the device
// fields are left for the caller.
TimingReport timing_report(const FrameTimingLog& log);

// ---- memory.json ----

struct VolumeStats {
  scene::VolumeShading shading;
  uint64_t density_atlas_bytes = 0;
  uint64_t lighting_cache_cells = 0;  // 0 unless the shading is fast
};

struct MemoryReport {
  uint64_t transient_bytes_aliased = 0, transient_bytes_unaliased = 0;
  uint64_t heap_count = 0;
  std::vector<passes::LightShadowStats> lights;
  scene::Bounds scene_bounds;
  uint64_t frames_with_capture_overflow = 0;
  VolumeStats volumes;
};

// Built by memory_report() in capture/frame_outputs.h.

// ---- the compiled frame graph (graph.json is the plan's own CompiledPlan::to_json) ----

struct PlanPassSummary {
  std::string name;
  rg::QueueType queue = rg::QueueType::Graphics;
  size_t barrier_count = 0;  // before the pass
};

struct PlanResourceSummary {
  std::string name;
  rg::ResourceKind kind = rg::ResourceKind::Texture;
  std::string description;  // "1920x1080 R16G16B16A16_SFLOAT", "4096 bytes"
  bool imported = false, used = false;
  uint64_t size = 0, offset = 0;
  std::optional<uint32_t> heap;                   // used transients only
  std::optional<uint32_t> first_pass, last_pass;  // positions in PlanSummary::passes
};

struct PlanSummary {
  std::vector<PlanPassSummary> passes;  // execution order
  std::vector<std::string> culled_passes;
  std::vector<PlanResourceSummary> resources;  // the plan's resource indices
  uint32_t barrier_count = 0;                  // final barriers included
  size_t final_barrier_count = 0;
  uint64_t heap_count = 0;
  rg::CompileOptions options;
  uint64_t shape_hash = 0;
};

PlanSummary plan_summary(const rg::CompiledPlan& plan);

// ---- quality.json (--compare-to uncompressed) ----

// QualityReport: capture/quality.h.

// ---- resolution.json (--measure-resolution) ----

// ResolutionReport: capture/resolution.h.

// ---- probes.json (--probe) ----

struct ProbeLight {
  std::string light;
  scene::ShadowSettings settings;  // technique, nodes, filter, sort and resolution are written
  std::vector<float> transmittance;  // one per point
};

struct ProbeReport {
  std::vector<glm::vec3> points;
  std::vector<ProbeLight> lights;
};

// ---- settings.json (avsm-capture) ----

// One light's shadow settings as the capture rendered it: the scene file's, with the
// command line's overrides applied (scene::ShadowOverrides::apply(Light&)).
struct LightSettings {
  std::string light;  // the light's name; "light <index>" when it has none (as in memory.json)
  scene::LightType type = scene::LightType::directional;
  scene::ShadowSettings shadow;  // every field is written; shadow.resolution is the one asked for
  // The resolution the map budget lowered shadow.resolution to (shadows.fit_budget); 0: not lowered.
  uint32_t lowered_to = 0;
};

// What a capture was made with: the settings two captures must share for their figures to
// compare (the regression gate lists those that differ, sweep/compare.h). The device is
// not one of them (timings.json names it): a baseline may come from another machine.
struct SettingsReport {
  // The scene file as "<its folder's name>/<its name>" ("default/scene.json",
  // "examples/alpha_casters.scene.json"), so that two checkouts or build folders compare
  // equal: scene_label().
  std::string scene;
  std::string camera;  // the camera's name as picked; its index when it has no name
  uint32_t width = 0, height = 0;
  uint32_t frames = 0, frames_in_flight = 0;
  float orbit_degrees = 0.0f;  // --orbit: the camera turned this much per frame
  float light_orbit_degrees = 0.0f;  // --light-orbit: the lights turned this much per frame
  std::optional<float> time;  // the instant written (--time, a shot's last frame): the animation posed there
  bool validation = false;
  scene::VolumeShading volume_shading;  // the scene's, with --volume-shading & co. applied
  bool compare_volume_shading = false;
  bool exponential_interpolation = false;
  bool compare_to_uncompressed = false;  // --compare-to uncompressed (keeps the exact lists)
  uint32_t probe_points = 0;             // --probe: the points' count
  std::vector<std::string> plot_texels;  // --plot-texel, as given (keeps the exact lists)
  scene::SceneShadows shadows;           // the scene file's "shadows" block (budget, clusters)
  std::vector<LightSettings> lights;     // in the scene's order
};

// "<parent folder name>/<file name>" of `scene_file` made absolute (lexically, without
// touching the disk): what SettingsReport::scene holds.
std::string scene_label(const std::filesystem::path& scene_file);

// ---- the whole frame ----

struct FrameReport {
  TimingReport timings;
  MemoryReport memory;
  // Not read back from disk: graph.json and graph.dot are the frame graph's own formats.
  PlanSummary plan;
  std::string plan_dot;  // CompiledPlan::to_dot()
  std::optional<QualityReport> quality;
  std::optional<ProbeReport> probes;
  std::optional<ResolutionReport> resolution;  // --measure-resolution
  // settings.json: written by avsm-capture (not by the viewer's screenshots); absent in
  // capture folders written before it existed.
  std::optional<SettingsReport> settings;
  std::optional<ShotReport> shot;  // --frame-range: the shot's frames, times and video
};

nlohmann::json to_json(const TimingReport& timings);
nlohmann::json to_json(const MemoryReport& memory);
nlohmann::json to_json(const QualityReport& quality);
nlohmann::json to_json(const ResolutionReport& resolution);
nlohmann::json to_json(const ProbeReport& probes);
nlohmann::json to_json(const SettingsReport& settings);
// Throw std::runtime_error naming the first key that is missing or of the wrong type.
TimingReport timing_report_from_json(const nlohmann::json& in);
MemoryReport memory_report_from_json(const nlohmann::json& in);
QualityReport quality_report_from_json(const nlohmann::json& in);
ResolutionReport resolution_report_from_json(const nlohmann::json& in);
ProbeReport probe_report_from_json(const nlohmann::json& in);
SettingsReport settings_report_from_json(const nlohmann::json& in);

// timings.json and memory.json from out_dir (required), settings.json, quality.json,
// resolution.json and probes.json when there; the plan summary and its dot text stay empty. Throws std::runtime_error
// naming the file.
FrameReport read_frame_report(const std::filesystem::path& out_dir);

}  // namespace avsm::capture
