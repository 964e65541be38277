#include "capture/frame_report.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <rendergraph/vk_names.h>
#include <stdexcept>

#include "capture/frame_outputs.h"
#include "capture/json_read.h"
#include "capture/pass_stages.h"
#include "passes/shadows/techniques/techniques.h"

namespace avsm::capture {
namespace fs = std::filesystem;
using nlohmann::json;

namespace {

rg::QueueType queue_from_string(const std::string& name) {
  for (rg::QueueType queue : {rg::QueueType::Graphics, rg::QueueType::Compute, rg::QueueType::Transfer})
    if (name == rg::to_string(queue)) return queue;
  throw std::runtime_error("unknown queue '" + name + "'");
}

// Only AVSM lights report a node count (quality.json's "nodes").
bool stores_avsm_nodes(const std::string& technique) {
  const passes::ShadowTechnique* t = passes::find_shadow_technique(technique);
  return t && t->stores_avsm_nodes();
}

std::string technique_from_json(const json& object) {
  const std::string name = value_of<std::string>(object, "technique");
  if (!passes::find_shadow_technique(name)) throw std::runtime_error("unknown technique '" + name + "'");
  return name;
}

scene::ShadowFilter filter_from_json(const json& object) {
  const std::string name = value_of<std::string>(object, "filter");
  if (auto filter = scene::shadow_filter_from_string(name)) return *filter;
  throw std::runtime_error("unknown filter '" + name + "'");
}

// Reports written before the fixed build existed have no "build": they were lists.
scene::ShadowBuild build_from_json(const json& object) {
  if (!object.contains("build")) return scene::ShadowBuild::lists;
  const std::string name = value_of<std::string>(object, "build");
  if (auto build = scene::shadow_build_from_string(name)) return *build;
  throw std::runtime_error("unknown shadow build '" + name + "'");
}

std::string map_kind_from_json(const json& object) {
  const std::string kind = value_of<std::string>(object, "map_kind");
  if (kind != "single" && kind != "cube" && kind != "cascades" && kind != "clusters" && kind != "virtual")
    throw std::runtime_error("unknown map kind '" + kind + "' (single, cube, cascades, clusters or virtual)");
  return kind;
}

json vec3_json(const glm::vec3& v) { return json::array({v.x, v.y, v.z}); }

// Components written as null (an empty box's infinities) keep `v`'s own.
void read_vec3(const json& array, glm::vec3& v) {
  if (!array.is_array() || array.size() != 3) throw std::runtime_error("expected [x, y, z]");
  for (int i = 0; i < 3; ++i) v[i] = number_or(array[size_t(i)], v[i]);
}

// ---- timings.json ----

json to_json(const Spread& s) { return {{"min", s.min}, {"median", s.median}, {"max", s.max}}; }

Spread spread_from_json(const json& in) {
  return {value_of<double>(in, "min"), value_of<double>(in, "median"), value_of<double>(in, "max")};
}

// "stage" is derived from the name (capture/pass_stages.h), written for scripts that sum
// per-stage times (bench/avsm/techniques.py) and not read back.
json to_json(const PassTiming& pass) {
  return {{"name", pass.name},
          {"stage", std::string(to_string(pass_stage(pass.name)))},
          {"queue", rg::to_string(pass.queue)},
          {"gpu_ms", to_json(pass.gpu_ms)},
          {"cpu_record_ms", to_json(pass.cpu_record_ms)}};
}

PassTiming pass_timing_from_json(const json& in) {
  return {value_of<std::string>(in, "name"), queue_from_string(value_of<std::string>(in, "queue")),
          spread_from_json(member(in, "gpu_ms")), spread_from_json(member(in, "cpu_record_ms"))};
}

json to_json(const FrameSample& frame) {
  return {{"gpu_ms", frame.gpu_ms},
          {"wall_ms", frame.wall_ms},
          {"submit_wall_ms", frame.submit_wall_ms},
          {"shadow_gpu_ms", frame.shadow_gpu_ms},
          {"inspection_gpu_ms", frame.inspection_gpu_ms},
          {"pages_built", frame.pages_built},
          {"pages_pending", frame.pages_pending},
          {"shadow_step_gpu_ms", frame.shadow_step_gpu_ms}};
}

FrameSample frame_sample_from_json(const json& in) {
  FrameSample frame{value_of<double>(in, "gpu_ms"), value_of<double>(in, "wall_ms"),
                    value_of<double>(in, "submit_wall_ms")};
  // 0 in reports written before they were recorded (a baseline from an older build).
  if (in.contains("shadow_gpu_ms")) frame.shadow_gpu_ms = value_of<double>(in, "shadow_gpu_ms");
  if (in.contains("inspection_gpu_ms")) frame.inspection_gpu_ms = value_of<double>(in, "inspection_gpu_ms");
  if (in.contains("pages_built")) frame.pages_built = value_of<uint32_t>(in, "pages_built");
  if (in.contains("pages_pending")) frame.pages_pending = value_of<uint32_t>(in, "pages_pending");
  if (in.contains("shadow_step_gpu_ms"))
    for (const auto& [step, ms] : member(in, "shadow_step_gpu_ms").items()) frame.shadow_step_gpu_ms[step] = ms.get<double>();
  return frame;
}

// ---- memory.json ----

json to_json(const passes::LightShadowStats& s) {
  json out = {{"light", s.light},
              {"technique", s.technique},
              {"nodes", s.nodes},
              {"resolution", s.resolution},
              {"mip_levels", s.mip_levels},
              {"map_kind", s.map_kind},
              {"maps", s.maps},
              {"lowered_from", s.lowered_from},
              {"map_bytes", s.map_bytes},
              {"capture_bytes", s.capture_bytes},
              {"capture_capacity_segments", s.capture_capacity},
              {"capture_requested_segments", s.capture_requested},
              {"capture_overflowed", s.overflowed},
              {"next_capture_capacity_segments", s.next_capture_capacity}};
  if (s.dsm_pool) {
    out["dsm_pool_capacity_nodes"] = s.dsm_pool->capacity_nodes;
    out["dsm_pool_requested_nodes"] = s.dsm_pool->requested_nodes;
    out["dsm_pool_overflowed"] = s.dsm_pool->overflowed;
    out["dsm_build_dispatches"] = s.dsm_pool->build_dispatches;
    out["dsm_build_needed_dispatches"] = s.dsm_pool->needed_dispatches;
    out["dsm_build_cut_short"] = s.dsm_pool->build_cut_short;
    out["dsm_pool_held_by_budget"] = s.dsm_pool->held_by_budget;
  }
  if (s.fixed_build) {
    const passes::FixedBuildStats& f = *s.fixed_build;
    out["fixed_build"] = {{"inserted_segments", f.inserted_segments},
                          {"light_depth_bytes", f.light_depth_bytes},
                          {"hair_bin_bytes", f.hair_bin_bytes},
                          {"hair_bin_capacity_entries", f.hair_bin_capacity},
                          {"hair_bin_requested_entries", f.hair_bin_requested},
                          {"tiles_walked_whole", f.tiles_walked},
                          {"transient_bytes", f.transient_bytes()}};
  }
  if (s.pages) {
    const passes::PageStats& p = *s.pages;
    out["pages"] = {{"pool_slots", p.slots},       {"requested", p.requested}, {"resident", p.resident},
                    {"built", p.built},            {"invalidated", p.invalidated}, {"evicted", p.evicted},
                    {"pending", p.pending},        {"unserved", p.unserved},   {"lod_bias", p.lod_bias}};
  }
  return out;
}

passes::LightShadowStats light_stats_from_json(const json& in) {
  passes::LightShadowStats s;
  s.light = value_of<std::string>(in, "light");
  s.technique = technique_from_json(in);
  s.nodes = value_of<uint32_t>(in, "nodes");
  s.resolution = value_of<uint32_t>(in, "resolution");
  s.mip_levels = value_of<uint32_t>(in, "mip_levels");
  // Reports written before lights had several maps: one map, never lowered.
  if (in.contains("map_kind")) s.map_kind = map_kind_from_json(in);
  if (in.contains("maps")) s.maps = value_of<uint32_t>(in, "maps");
  if (in.contains("lowered_from")) s.lowered_from = value_of<uint32_t>(in, "lowered_from");
  s.map_bytes = value_of<uint64_t>(in, "map_bytes");
  s.capture_bytes = value_of<uint64_t>(in, "capture_bytes");
  s.capture_capacity = value_of<uint64_t>(in, "capture_capacity_segments");
  s.capture_requested = value_of<uint64_t>(in, "capture_requested_segments");
  s.overflowed = value_of<bool>(in, "capture_overflowed");
  s.next_capture_capacity = value_of<uint64_t>(in, "next_capture_capacity_segments");
  if (in.contains("dsm_pool_capacity_nodes"))
    s.dsm_pool = passes::DsmPoolStats{value_of<uint64_t>(in, "dsm_pool_requested_nodes"),
                                      value_of<uint64_t>(in, "dsm_pool_capacity_nodes"),
                                      value_of<bool>(in, "dsm_pool_overflowed")};
  if (in.contains("dsm_build_dispatches")) {  // reports from before the build was several dispatches: none
    s.dsm_pool->build_dispatches = value_of<uint32_t>(in, "dsm_build_dispatches");
    s.dsm_pool->needed_dispatches = value_of<uint32_t>(in, "dsm_build_needed_dispatches");
    s.dsm_pool->build_cut_short = value_of<bool>(in, "dsm_build_cut_short");
  }
  if (in.contains("dsm_pool_held_by_budget")) s.dsm_pool->held_by_budget = value_of<bool>(in, "dsm_pool_held_by_budget");
  if (in.contains("fixed_build")) {
    const json& f = in.at("fixed_build");
    s.fixed_build = passes::FixedBuildStats{
        value_of<uint64_t>(f, "inserted_segments"),          value_of<uint64_t>(f, "light_depth_bytes"),
        value_of<uint64_t>(f, "hair_bin_bytes"),             value_of<uint64_t>(f, "hair_bin_capacity_entries"),
        value_of<uint64_t>(f, "hair_bin_requested_entries"), value_of<uint64_t>(f, "tiles_walked_whole")};
  }
  if (in.contains("pages")) {
    const json& p = in.at("pages");
    s.pages = passes::PageStats{value_of<uint32_t>(p, "pool_slots"), value_of<uint32_t>(p, "requested"),
                                value_of<uint32_t>(p, "resident"),   value_of<uint32_t>(p, "built"),
                                value_of<uint32_t>(p, "invalidated"), value_of<uint32_t>(p, "evicted"),
                                value_of<uint32_t>(p, "pending"),    value_of<uint32_t>(p, "unserved"),
                                value_of<float>(p, "lod_bias")};
  }
  return s;
}

json to_json(const VolumeStats& v) {
  return {{"shading", scene::to_string(v.shading.mode)},
          {"resolution_divisor", v.shading.resolution_divisor},
          {"step_voxels", v.shading.step_voxels},
          {"density_atlas_bytes", v.density_atlas_bytes},
          {"lighting_cache_cells", v.lighting_cache_cells}};
}

VolumeStats volume_stats_from_json(const json& in) {
  VolumeStats v;
  const std::string mode = value_of<std::string>(in, "shading");
  const auto parsed = scene::volume_shading_mode_from_string(mode);
  if (!parsed) throw std::runtime_error("unknown volume shading '" + mode + "'");
  v.shading.mode = *parsed;
  v.shading.resolution_divisor = value_of<int>(in, "resolution_divisor");
  v.shading.step_voxels = value_of<float>(in, "step_voxels");
  v.density_atlas_bytes = value_of<uint64_t>(in, "density_atlas_bytes");
  v.lighting_cache_cells = value_of<uint64_t>(in, "lighting_cache_cells");
  return v;
}

// ---- quality.json ----

// No receivers: no error to speak of (null rather than a made-up 0).
json mean_json(const ErrorStats& s) { return s.receivers ? json(s.mean()) : json(nullptr); }
json max_json(const ErrorStats& s) { return s.receivers ? json(s.max) : json(nullptr); }

json to_json(const ErrorStats& s) {
  return {{"receivers", s.receivers}, {"mean_abs_error", mean_json(s)}, {"max_abs_error", max_json(s)}};
}

// The file keeps the mean, not the sum: the sum read back is mean x receivers.
ErrorStats error_stats_from_json(const json& in) {
  ErrorStats s;
  s.receivers = value_of<uint64_t>(in, "receivers");
  s.sum = number_or(member(in, "mean_abs_error"), 0.0) * double(s.receivers);
  s.max = number_or(member(in, "max_abs_error"), 0.0);
  return s;
}

json to_json(const LightQuality& q, size_t index) {
  const ErrorStats all = q.all();
  return {
      {"light", q.light},
      {"index", index},
      {"technique", q.settings.technique},
      {"technique_label", technique_label(q.settings)},
      {"filter", scene::to_string(q.settings.filter)},
      {"sort", q.settings.sort},
      {"build", scene::to_string(q.settings.build)},
      {"resolution", q.settings.resolution},
      {"error_image", error_image_name(index)},
      {"receivers",
       {{"surface", q.surface.receivers}, {"smoke", q.smoke.receivers}, {"hair", q.hair.receivers},
        {"total", all.receivers}}},
      {"surface", to_json(q.surface)},
      {"smoke", to_json(q.smoke)},
      {"hair", to_json(q.hair)},
      // AVSM keeps N nodes per texel (the other techniques' sizes are in technique_label and parameters).
      {"nodes", stores_avsm_nodes(q.settings.technique) ? json(q.settings.nodes) : json(nullptr)},
      {"parameters", q.settings.parameters},
      {"mean_abs_error", mean_json(all)},
      {"max_abs_error", max_json(all)},
  };
}

LightQuality light_quality_from_json(const json& in) {
  LightQuality q;
  q.light = value_of<std::string>(in, "light");
  q.settings.technique = technique_from_json(in);
  q.settings.filter = filter_from_json(in);
  q.settings.sort = value_of<bool>(in, "sort");
  q.settings.build = build_from_json(in);
  q.settings.resolution = value_of<int>(in, "resolution");
  q.settings.nodes = number_or(member(in, "nodes"), q.settings.nodes);
  q.settings.parameters = value_of<std::map<std::string, double>>(in, "parameters");
  q.surface = error_stats_from_json(member(in, "surface"));
  q.smoke = error_stats_from_json(member(in, "smoke"));
  q.hair = error_stats_from_json(member(in, "hair"));
  return q;
}

// ---- probes.json ----

json to_json(const ProbeLight& light) {
  const scene::ShadowSettings& s = light.settings;
  return {{"light", light.light},
          {"technique", s.technique},
          {"nodes", s.nodes},
          {"filter", scene::to_string(s.filter)},
          {"sort", s.sort},
          {"build", scene::to_string(s.build)},
          {"resolution", s.resolution},
          {"transmittance", light.transmittance}};
}

ProbeLight probe_light_from_json(const json& in) {
  ProbeLight light;
  light.light = value_of<std::string>(in, "light");
  light.settings.technique = technique_from_json(in);
  light.settings.nodes = value_of<int>(in, "nodes");
  light.settings.filter = filter_from_json(in);
  light.settings.sort = value_of<bool>(in, "sort");
  light.settings.build = build_from_json(in);
  light.settings.resolution = value_of<int>(in, "resolution");
  light.transmittance = value_of<std::vector<float>>(in, "transmittance");
  return light;
}

// ---- settings.json ----

scene::LightType light_type_from_json(const json& object) {
  const std::string name = value_of<std::string>(object, "type");
  for (scene::LightType type :
       {scene::LightType::directional, scene::LightType::spot, scene::LightType::point, scene::LightType::rect,
        scene::LightType::disk, scene::LightType::sphere})
    if (name == scene::to_string(type)) return type;
  throw std::runtime_error("unknown light type '" + name + "'");
}

scene::ShadowKernel kernel_from_json(const json& object) {
  const std::string name = value_of<std::string>(object, "kernel");
  if (auto kernel = scene::shadow_kernel_from_string(name)) return *kernel;
  throw std::runtime_error("unknown kernel '" + name + "'");
}

scene::ShadowFit fit_from_json(const json& object) {
  const std::string name = value_of<std::string>(object, "fit");
  if (auto fit = scene::shadow_fit_from_string(name)) return *fit;
  throw std::runtime_error("unknown shadow fit '" + name + "'");
}

json to_json(const LightSettings& light) {
  const scene::ShadowSettings& s = light.shadow;
  return {{"light", light.light},
          {"type", scene::to_string(light.type)},
          {"technique", s.technique},
          {"nodes", s.nodes},
          {"resolution", s.resolution},
          {"lowered_to", light.lowered_to},
          {"filter", scene::to_string(s.filter)},
          {"kernel", scene::to_string(s.kernel)},
          {"kernel_radius", s.kernel_radius},
          {"sort", s.sort},
          {"build", scene::to_string(s.build)},
          {"fit", scene::to_string(s.fit)},
          {"distance", s.distance},
          {"cascades", s.cascades},
          {"cascade_blend", s.cascade_blend},
          {"clusters", s.clusters},
          {"layout", scene::to_string(s.layout)},
          {"virtual_resolution", s.virtual_resolution},
          {"page_size", s.page_size},
          {"page_pool_mib", s.page_pool_mib},
          {"page_lod_bias", s.page_lod_bias},
          {"page_volume_lod_bias", s.page_volume_lod_bias},
          {"parameters", s.parameters}};
}

LightSettings light_settings_from_json(const json& in) {
  LightSettings light;
  light.light = value_of<std::string>(in, "light");
  light.type = light_type_from_json(in);
  scene::ShadowSettings& s = light.shadow;
  s.technique = technique_from_json(in);
  s.nodes = value_of<int>(in, "nodes");
  s.resolution = value_of<int>(in, "resolution");
  light.lowered_to = value_of<uint32_t>(in, "lowered_to");
  s.filter = filter_from_json(in);
  s.kernel = kernel_from_json(in);
  s.kernel_radius = value_of<int>(in, "kernel_radius");
  s.sort = value_of<bool>(in, "sort");
  s.build = build_from_json(in);
  s.fit = fit_from_json(in);
  s.distance = value_of<float>(in, "distance");
  s.cascades = value_of<int>(in, "cascades");
  s.cascade_blend = value_of<float>(in, "cascade_blend");
  s.clusters = value_of<int>(in, "clusters");
  if (in.contains("layout")) {  // reports from before paged maps: dense
    const std::string layout = value_of<std::string>(in, "layout");
    const auto parsed = scene::shadow_layout_from_string(layout);
    if (!parsed) throw std::runtime_error("unknown shadow layout '" + layout + "'");
    s.layout = *parsed;
    s.virtual_resolution = value_of<int>(in, "virtual_resolution");
    s.page_size = value_of<int>(in, "page_size");
    s.page_pool_mib = value_of<double>(in, "page_pool_mib");
    s.page_lod_bias = value_of<float>(in, "page_lod_bias");
    // Reports from before volume receivers asked for pages: the default.
    if (in.contains("page_volume_lod_bias")) s.page_volume_lod_bias = value_of<float>(in, "page_volume_lod_bias");
  }
  s.parameters = value_of<std::map<std::string, double>>(in, "parameters");
  return light;
}

// ---- the plan ----

// As CompiledPlan::to_json's "desc": "1920x1080 R16G16B16A16_SFLOAT", "256x256x64 ... mips 9", "4096 bytes".
std::string describe(const rg::PlannedResource& r) {
  if (r.kind == rg::ResourceKind::Buffer) return std::to_string(r.buffer.size) + " bytes";
  const rg::TextureDesc& d = r.texture;
  // Appended piece by piece: "x" + std::to_string(...) trips GCC 12's -Wrestrict
  // false positive once this is inlined.
  std::string text = std::to_string(d.width);
  text.append("x").append(std::to_string(d.height));
  if (d.depth > 1) text.append("x").append(std::to_string(d.depth));
  text.append(" ").append(rg::format_name(d.format));
  if (d.mip_levels > 1) text.append(" mips ").append(std::to_string(d.mip_levels));
  if (d.array_layers > 1) text.append(" layers ").append(std::to_string(d.array_layers));
  return text;
}

std::optional<uint32_t> index_or_none(uint32_t index) {
  return index == rg::kInvalidIndex ? std::nullopt : std::optional<uint32_t>(index);
}

PlanResourceSummary summarize(const rg::PlannedResource& r) {
  return {r.name,   r.kind,   describe(r),           r.imported,           r.used,
          r.size,   r.offset, index_or_none(r.heap), index_or_none(r.first_pass), index_or_none(r.last_pass)};
}

}  // namespace

Spread spread_of(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  return {values.front(), values[values.size() / 2], values.back()};
}

std::optional<double> TimingReport::median_gpu_ms(const std::string& pass) const {
  for (const PassTiming& timing : passes)
    if (timing.name == pass) return timing.gpu_ms.median;
  return std::nullopt;
}

TimingReport timing_report(const FrameTimingLog& log) {
  TimingReport report;
  for (const FrameTimingLog::PassSamples& pass : log.passes())
    report.passes.push_back({pass.name, pass.queue, spread_of(pass.gpu_ms), spread_of(pass.cpu_record_ms)});
  report.frames = log.frames();
  const auto spread_over_frames = [&](double FrameSample::*figure) {
    std::vector<double> values;
    for (const FrameSample& frame : report.frames) values.push_back(frame.*figure);
    return spread_of(std::move(values));
  };
  report.frame_gpu_ms = spread_over_frames(&FrameSample::gpu_ms);
  report.frame_wall_ms = spread_over_frames(&FrameSample::wall_ms);
  report.frame_submit_wall_ms = spread_over_frames(&FrameSample::submit_wall_ms);
  return report;
}

PlanSummary plan_summary(const rg::CompiledPlan& plan) {
  PlanSummary summary;
  for (const rg::PlannedPass& pass : plan.passes) summary.passes.push_back({pass.name, pass.queue, pass.barriers.size()});
  for (const rg::PlannedPass& pass : plan.culled_passes) summary.culled_passes.push_back(pass.name);
  for (const rg::PlannedResource& resource : plan.resources) summary.resources.push_back(summarize(resource));
  summary.barrier_count = plan.stats.barrier_count;
  summary.final_barrier_count = plan.final_barriers.size();
  summary.heap_count = plan.heaps.size();
  summary.options = plan.options;
  summary.shape_hash = plan.shape_hash;
  return summary;
}

json to_json(const TimingReport& t) {
  json passes = json::array(), frames = json::array();
  for (const PassTiming& pass : t.passes) passes.push_back(to_json(pass));
  for (const FrameSample& frame : t.frames) frames.push_back(to_json(frame));
  return {{"device", t.device},
          {"driver", t.driver},
          {"timestamp_mode", t.timestamp_mode},
          {"cpu_device", t.cpu_device},
          {"width", t.width},
          {"height", t.height},
          {"frames_measured", t.frames.size()},
          {"passes", passes},
          {"frame_gpu_ms", to_json(t.frame_gpu_ms)},
          {"frame_wall_ms", to_json(t.frame_wall_ms)},
          {"frame_submit_wall_ms", to_json(t.frame_submit_wall_ms)},
          {"frames", frames}};
}

TimingReport timing_report_from_json(const json& in) {
  TimingReport t;
  t.device = value_of<std::string>(in, "device");
  t.driver = value_of<std::string>(in, "driver");
  t.timestamp_mode = value_of<std::string>(in, "timestamp_mode");
  if (in.contains("cpu_device")) t.cpu_device = value_of<bool>(in, "cpu_device");
  t.width = value_of<uint32_t>(in, "width");
  t.height = value_of<uint32_t>(in, "height");
  t.passes = array_of<PassTiming>(in, "passes", pass_timing_from_json);
  t.frame_gpu_ms = spread_from_json(member(in, "frame_gpu_ms"));
  t.frame_wall_ms = spread_from_json(member(in, "frame_wall_ms"));
  t.frame_submit_wall_ms = spread_from_json(member(in, "frame_submit_wall_ms"));
  t.frames = array_of<FrameSample>(in, "frames", frame_sample_from_json);
  return t;
}

json to_json(const MemoryReport& m) {
  json lights = json::array();
  for (const passes::LightShadowStats& light : m.lights) lights.push_back(to_json(light));
  return {{"transient_bytes_aliased", m.transient_bytes_aliased},
          {"transient_bytes_unaliased", m.transient_bytes_unaliased},
          {"heaps", m.heap_count},
          {"lights", lights},
          {"scene_bounds", {{"min", vec3_json(m.scene_bounds.min)}, {"max", vec3_json(m.scene_bounds.max)}}},
          {"frames_with_capture_overflow", m.frames_with_capture_overflow},
          {"volumes", to_json(m.volumes)}};
}

MemoryReport memory_report_from_json(const json& in) {
  MemoryReport m;
  m.transient_bytes_aliased = value_of<uint64_t>(in, "transient_bytes_aliased");
  m.transient_bytes_unaliased = value_of<uint64_t>(in, "transient_bytes_unaliased");
  m.heap_count = value_of<uint64_t>(in, "heaps");
  m.lights = array_of<passes::LightShadowStats>(in, "lights", light_stats_from_json);
  const json& bounds = member(in, "scene_bounds");
  read_vec3(member(bounds, "min"), m.scene_bounds.min);
  read_vec3(member(bounds, "max"), m.scene_bounds.max);
  m.frames_with_capture_overflow = value_of<uint64_t>(in, "frames_with_capture_overflow");
  m.volumes = volume_stats_from_json(member(in, "volumes"));
  return m;
}

json to_json(const QualityReport& q) {
  json lights = json::array();
  for (size_t i = 0; i < q.lights.size(); ++i) lights.push_back(to_json(q.lights[i], i));
  return {
      {"reference", "uncompressed"},
      {"error", "absolute transmittance difference |T - T_ref| between the light's technique and its exact "
                "capture lists, both looked up with the light's filter"},
      {"width", q.width},
      {"height", q.height},
      {"error_image_scale", kErrorImageScale},
      {"error_image_colours", kErrorImageColours},
      {"receiver_kinds",
       {{"surface", surface_receivers_rule()}, {"smoke", smoke_receivers_rule()}, {"hair", hair_receivers_rule()}}},
      {"lights", lights},
  };
}

QualityReport quality_report_from_json(const json& in) {
  return {value_of<uint32_t>(in, "width"), value_of<uint32_t>(in, "height"),
          array_of<LightQuality>(in, "lights", light_quality_from_json)};
}

// ---- resolution.json ----

json to_json(const LightResolution& r, size_t index) {
  return {
      {"light", r.light},
      {"index", index},
      {"paged", r.paged},
      {"receivers", r.receivers},
      {"matched", r.matched},
      {"matched_fraction", r.matched_fraction()},
      {"median_texel_pixels", r.median_texel_pixels},
      {"p95_texel_pixels", r.p95_texel_pixels},
      {"needed_texels", r.needed_texels},
      {"receivers_per_level", r.levels},
      {"image", resolution_image_name(index)},
  };
}

LightResolution light_resolution_from_json(const json& in) {
  LightResolution r;
  r.light = value_of<std::string>(in, "light");
  r.paged = value_of<bool>(in, "paged");
  r.receivers = value_of<uint64_t>(in, "receivers");
  r.matched = value_of<uint64_t>(in, "matched");
  r.median_texel_pixels = value_of<double>(in, "median_texel_pixels");
  r.p95_texel_pixels = value_of<double>(in, "p95_texel_pixels");
  r.needed_texels = value_of<double>(in, "needed_texels");
  r.levels = value_of<std::vector<uint64_t>>(in, "receivers_per_level");
  return r;
}

json to_json(const ResolutionReport& r) {
  json lights = json::array();
  for (size_t i = 0; i < r.lights.size(); ++i) lights.push_back(to_json(r.lights[i], i));
  return {
      {"texel_pixels",
       "the widest a texel of the level a surface lookup reads is on screen, in pixels, at each camera pixel's "
       "opaque surface the light reaches (trilinear: the blended level)"},
      {"matched_texel_pixels", kMatchedTexelPixels},
      {"needed_texels",
       "per light: the texels a map whose square texels are just matched_texel_pixels wide at every receiver "
       "would spend on the receivers (each pixel's area in the map over such a texel's): the least any map of "
       "square texels needs to meet the target, set by how anisotropic the receivers' footprints are"},
      {"image_colours", kResolutionImageColours},
      {"width", r.width},
      {"height", r.height},
      {"receivers", r.receivers()},
      {"matched", r.matched()},
      {"matched_fraction", r.matched_fraction()},
      {"lights", lights},
  };
}

ResolutionReport resolution_report_from_json(const json& in) {
  return {value_of<uint32_t>(in, "width"), value_of<uint32_t>(in, "height"),
          array_of<LightResolution>(in, "lights", light_resolution_from_json)};
}

json to_json(const ProbeReport& p) {
  json points = json::array(), lights = json::array();
  for (const glm::vec3& point : p.points) points.push_back(vec3_json(point));
  for (const ProbeLight& light : p.lights) lights.push_back(to_json(light));
  return {{"points", points}, {"lights", lights}};
}

ProbeReport probe_report_from_json(const json& in) {
  ProbeReport p;
  p.points = array_of<glm::vec3>(in, "points", [](const nlohmann::json& item) {
    glm::vec3 point(0.0f);
    read_vec3(item, point);
    return point;
  });
  p.lights = array_of<ProbeLight>(in, "lights", probe_light_from_json);
  return p;
}

std::string scene_label(const fs::path& scene_file) {
  const fs::path file = fs::absolute(scene_file).lexically_normal();
  const fs::path folder = file.parent_path().filename();
  return (folder.empty() ? file.filename() : folder / file.filename()).generic_string();
}

json to_json(const SettingsReport& s) {
  json lights = json::array();
  for (const LightSettings& light : s.lights) lights.push_back(to_json(light));
  json out = {{"scene", s.scene},
          {"camera", s.camera},
          {"width", s.width},
          {"height", s.height},
          {"frames", s.frames},
          {"frames_in_flight", s.frames_in_flight},
          {"orbit_degrees", s.orbit_degrees},
          {"light_orbit_degrees", s.light_orbit_degrees},
          {"validation", s.validation},
          {"volume_shading",
           {{"mode", scene::to_string(s.volume_shading.mode)},
            {"resolution_divisor", s.volume_shading.resolution_divisor},
            {"step_voxels", s.volume_shading.step_voxels}}},
          {"compare_volume_shading", s.compare_volume_shading},
          {"exponential_interpolation", s.exponential_interpolation},
          {"compare_to_uncompressed", s.compare_to_uncompressed},
          {"probe_points", s.probe_points},
          {"plot_texels", s.plot_texels},
          {"shadows",
           {{"budget_mib", s.shadows.budget_mib}, {"fit_budget", s.shadows.fit_budget}, {"clusters", s.shadows.clusters}}},
          {"lights", lights}};
  if (s.time) out["time"] = *s.time;
  return out;
}

SettingsReport settings_report_from_json(const json& in) {
  SettingsReport s;
  s.scene = value_of<std::string>(in, "scene");
  s.camera = value_of<std::string>(in, "camera");
  s.width = value_of<uint32_t>(in, "width");
  s.height = value_of<uint32_t>(in, "height");
  s.frames = value_of<uint32_t>(in, "frames");
  s.frames_in_flight = value_of<uint32_t>(in, "frames_in_flight");
  if (in.contains("orbit_degrees")) s.orbit_degrees = value_of<float>(in, "orbit_degrees");  // 0 before it was recorded
  if (in.contains("light_orbit_degrees")) s.light_orbit_degrees = value_of<float>(in, "light_orbit_degrees");
  if (in.contains("time")) s.time = value_of<float>(in, "time");
  s.validation = value_of<bool>(in, "validation");
  const json& volumes = member(in, "volume_shading");
  const std::string mode = value_of<std::string>(volumes, "mode");
  const auto parsed = scene::volume_shading_mode_from_string(mode);
  if (!parsed) throw std::runtime_error("unknown volume shading '" + mode + "'");
  s.volume_shading.mode = *parsed;
  s.volume_shading.resolution_divisor = value_of<int>(volumes, "resolution_divisor");
  s.volume_shading.step_voxels = value_of<float>(volumes, "step_voxels");
  s.compare_volume_shading = value_of<bool>(in, "compare_volume_shading");
  s.exponential_interpolation = value_of<bool>(in, "exponential_interpolation");
  s.compare_to_uncompressed = value_of<bool>(in, "compare_to_uncompressed");
  s.probe_points = value_of<uint32_t>(in, "probe_points");
  s.plot_texels = value_of<std::vector<std::string>>(in, "plot_texels");
  const json& shadows = member(in, "shadows");
  s.shadows.budget_mib = value_of<double>(shadows, "budget_mib");
  s.shadows.fit_budget = value_of<bool>(shadows, "fit_budget");
  s.shadows.clusters = value_of<int>(shadows, "clusters");
  s.lights = array_of<LightSettings>(in, "lights", light_settings_from_json);
  return s;
}

FrameReport read_frame_report(const fs::path& out_dir) {
  FrameReport report;
  report.timings = read_report_file(out_dir / "timings.json", timing_report_from_json);
  report.memory = read_report_file(out_dir / "memory.json", memory_report_from_json);
  std::error_code ec;
  if (fs::is_regular_file(out_dir / "quality.json", ec))
    report.quality = read_report_file(out_dir / "quality.json", quality_report_from_json);
  if (fs::is_regular_file(out_dir / "resolution.json", ec))
    report.resolution = read_report_file(out_dir / "resolution.json", resolution_report_from_json);
  if (fs::is_regular_file(out_dir / "probes.json", ec))
    report.probes = read_report_file(out_dir / "probes.json", probe_report_from_json);
  if (fs::is_regular_file(out_dir / "settings.json", ec))
    report.settings = read_report_file(out_dir / "settings.json", settings_report_from_json);
  return report;
}

}  // namespace avsm::capture
