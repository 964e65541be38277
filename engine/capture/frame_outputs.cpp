#include "capture/frame_outputs.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "capture/files.h"
#include "gpu/context.h"
#include "gpu/transfer.h"
#include "gpu/vk_check.h"
#include "io/image_io.h"
#include "passes/shadow_debug_pass.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"

namespace avsm::capture {
namespace fs = std::filesystem;

namespace {

double ms_between(std::chrono::steady_clock::time_point from, std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

struct Stats {
  double min = 0, median = 0, max = 0;
};

Stats stats_of(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  return {values.front(), values[values.size() / 2], values.back()};
}

nlohmann::json to_json(const Stats& s) { return {{"min", s.min}, {"median", s.median}, {"max", s.max}}; }

nlohmann::json frame_samples_json(const FrameTimingLog& log) {
  nlohmann::json frames = nlohmann::json::array();
  for (size_t i = 0; i < log.frame_gpu_ms().size(); ++i)
    frames.push_back({{"gpu_ms", log.frame_gpu_ms()[i]},
                      {"wall_ms", log.frame_wall_ms()[i]},
                      {"submit_wall_ms", log.frame_submit_ms()[i]}});
  return frames;
}

nlohmann::json timings_json(const FrameOutputSources& frame) {
  const FrameTimingLog& log = frame.timings;
  nlohmann::json passes = nlohmann::json::array();
  for (const FrameTimingLog::PassSamples& pass : log.passes())
    passes.push_back({{"name", pass.name},
                      {"queue", rg::to_string(pass.queue)},
                      {"gpu_ms", to_json(stats_of(pass.gpu_ms))},
                      {"cpu_record_ms", to_json(stats_of(pass.cpu_record_ms))}});
  return {
      {"device", frame.ctx.info().name},
      {"driver", frame.ctx.info().driver_name + " " + frame.ctx.info().driver_info},
      {"timestamp_mode", gpu::to_string(frame.executor.timestamp_mode())},
      {"width", frame.renderer.width()},
      {"height", frame.renderer.height()},
      {"frames_measured", log.frame_gpu_ms().size()},
      {"passes", passes},
      {"frame_gpu_ms", to_json(stats_of(log.frame_gpu_ms()))},
      {"frame_wall_ms", to_json(stats_of(log.frame_wall_ms()))},
      // Submit to completion on the CPU clock: what the GPU times of a frame add up to.
      {"frame_submit_wall_ms", to_json(stats_of(log.frame_submit_ms()))},
      {"frames", frame_samples_json(log)},
  };
}

nlohmann::json shadow_json(const passes::LightShadowStats& s) {
  nlohmann::json json = {{"light", s.light},
                         {"technique", scene::to_string(s.technique)},
                         {"nodes", s.nodes},
                         {"resolution", s.resolution},
                         {"mip_levels", s.mip_levels},
                         {"map_bytes", s.map_bytes},
                         {"capture_bytes", s.capture_bytes},
                         {"capture_capacity_segments", s.capture_capacity},
                         {"capture_requested_segments", s.capture_requested},
                         {"capture_overflowed", s.overflowed},
                         {"next_capture_capacity_segments", s.next_capture_capacity}};
  if (s.technique == scene::ShadowTechnique::dsm) {  // the deep shadow map's node pool
    json["dsm_pool_capacity_nodes"] = s.pool_capacity;
    json["dsm_pool_requested_nodes"] = s.pool_requested;
    json["dsm_pool_overflowed"] = s.pool_overflowed;
  }
  return json;
}

nlohmann::json memory_json(const FrameOutputSources& frame) {
  const rg::PlanStats& stats = frame.executor.plan().stats;
  nlohmann::json lights = nlohmann::json::array();
  for (const passes::LightShadowStats& light : frame.renderer.shadows().frame_stats())
    lights.push_back(shadow_json(light));
  const scene::Bounds& bounds = frame.scene.bounds;
  return {{"transient_bytes_aliased", stats.transient_bytes_aliased},
          {"transient_bytes_unaliased", stats.transient_bytes_unaliased},
          {"heaps", frame.executor.plan().heaps.size()},
          {"lights", lights},
          {"scene_bounds",
           {{"min", {bounds.min.x, bounds.min.y, bounds.min.z}}, {"max", {bounds.max.x, bounds.max.y, bounds.max.z}}}},
          {"frames_with_capture_overflow", frame.frames_with_capture_overflow},
          {"volumes",
           {{"shading", scene::to_string(frame.renderer.volume_shading().mode)},
            {"resolution_divisor", frame.renderer.volume_shading().resolution_divisor},
            {"step_voxels", frame.renderer.volume_shading().step_voxels},
            {"density_atlas_bytes", frame.renderer.density_atlas_bytes()},
            {"lighting_cache_cells", frame.renderer.lighting_cache_cells()}}}};
}

// light<i>_transmittance.png: each light's map as grey levels (passes/shadow_debug_pass.h).
void write_light_images(const FrameOutputSources& frame, const fs::path& out_dir) {
  const std::vector<gpu::Image>& images = frame.renderer.light_images();
  for (size_t i = 0; i < images.size() && i < frame.scene.lights.size(); ++i)
    io::write_png_raw(out_dir / ("light" + std::to_string(i) + "_transmittance.png"),
                      gpu::read_image(frame.ctx, images[i], passes::ShadowDebugPass::kOutputLayout));
}

}  // namespace

FrameClock render_timed_frame(gpu::Context& ctx, renderer::SceneRenderer& renderer, rg::vulkan::Executor& executor,
                              VkCommandBuffer cmd, const passes::View& view,
                              const std::function<void(VkCommandBuffer)>& also_record) {
  FrameClock clock;
  clock.start = std::chrono::steady_clock::now();
  rg::Graph graph = renderer.build_frame(executor, view);
  clock.built = std::chrono::steady_clock::now();
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  executor.record(graph, cmd);
  if (also_record) also_record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));
  clock.recorded = std::chrono::steady_clock::now();
  ctx.submit_and_wait(cmd);
  clock.completed = std::chrono::steady_clock::now();
  renderer.finish_frame();
  return clock;
}

FrameTimingLog::FrameTimingLog(std::chrono::steady_clock::time_point origin) : origin_(origin) {}

double FrameTimingLog::add_frame(const FrameClock& clock, const std::vector<rg::vulkan::PassTiming>& passes,
                                 bool measured) {
  const double wall = ms_between(clock.start, std::chrono::steady_clock::now());
  const double start = ms_between(origin_, clock.start), built = ms_between(origin_, clock.built);
  const double recorded = ms_between(origin_, clock.recorded), completed = ms_between(origin_, clock.completed);

  // The trace: CPU slices (build, record with a slice per pass, submit and wait) and,
  // per queue type, the passes' GPU times laid end to end from the submit.
  const std::string name = "frame " + std::to_string(++frames_logged_);
  trace_.add("CPU", name, start, completed - start, "frame");
  trace_.add("CPU", "build graph", start, built - start, "cpu");
  trace_.add("CPU", "record", built, recorded - built, "cpu");
  trace_.add("CPU", "submit + wait", recorded, completed - recorded, "cpu");
  double record_at = built, gpu_at = recorded;
  for (const rg::vulkan::PassTiming& pass : passes) {
    trace_.add("CPU record", pass.name, record_at, pass.cpu_record_ms, "cpu");
    record_at += pass.cpu_record_ms;
    trace_.add(std::string("GPU ") + rg::to_string(pass.queue) + " queue", pass.name, gpu_at, pass.gpu_ms, "gpu");
    gpu_at += pass.gpu_ms;
  }
  if (!measured) return wall;

  double total = 0;
  for (const rg::vulkan::PassTiming& pass : passes) {
    auto [found, added] = pass_index_.emplace(pass.name, passes_.size());
    if (added) passes_.push_back({pass.name, pass.queue, {}, {}});
    PassSamples& samples = passes_[found->second];
    samples.queue = pass.queue;
    samples.gpu_ms.push_back(pass.gpu_ms);
    samples.cpu_record_ms.push_back(pass.cpu_record_ms);
    total += pass.gpu_ms;
  }
  frame_gpu_ms_.push_back(total);
  frame_wall_ms_.push_back(wall);
  frame_submit_ms_.push_back(completed - recorded);
  return wall;
}

std::map<std::string, double> FrameTimingLog::median_gpu_ms() const {
  std::map<std::string, double> medians;
  for (const PassSamples& pass : passes_)
    if (!pass.gpu_ms.empty()) medians[pass.name] = stats_of(pass.gpu_ms).median;
  return medians;
}

void FrameTimingLog::clear() { *this = FrameTimingLog(std::chrono::steady_clock::now()); }

FrameOutputFiles write_frame_outputs(const fs::path& out_dir, const FrameOutputSources& frame) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw std::runtime_error(out_dir.string() + ": cannot create output folder: " + ec.message());

  FrameOutputFiles out{out_dir / "frame.png", out_dir / "frame.exr", out_dir / "timings.json"};
  io::write_png_raw(out.png, gpu::read_image(frame.ctx, frame.renderer.ldr(), renderer::SceneRenderer::kOutputLayout));
  io::write_exr(out.exr, gpu::read_image(frame.ctx, frame.renderer.hdr(), renderer::SceneRenderer::kOutputLayout));
  write_json(out.timings, timings_json(frame));
  frame.timings.trace().write(out_dir / "trace.json");
  write_light_images(frame, out_dir);
  write_text(out_dir / "graph.json", frame.executor.plan().to_json());
  write_text(out_dir / "graph.dot", frame.executor.plan().to_dot());
  write_json(out_dir / "memory.json", memory_json(frame));
  return out;
}

}  // namespace avsm::capture
