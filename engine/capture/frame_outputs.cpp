#include "capture/frame_outputs.h"

#include <algorithm>
#include <nlohmann/json.hpp>
#include <stdexcept>

#include "capture/files.h"
#include "capture/frame_report.h"
#include "capture/pass_stages.h"
#include "gpu/context.h"
#include "gpu/transfer.h"
#include "gpu/vk_check.h"
#include "io/image_io.h"
#include "passes/shadows/inspection/shadow_debug_pass.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"

namespace avsm::capture {
namespace fs = std::filesystem;

namespace {

double ms_between(std::chrono::steady_clock::time_point from, std::chrono::steady_clock::time_point to) {
  return std::chrono::duration<double, std::milli>(to - from).count();
}

TimingReport timing_report(const FrameOutputSources& frame) {
  TimingReport report = timing_report(frame.timings);
  report.device = frame.ctx.info().name;
  report.driver = frame.ctx.info().driver_name + " " + frame.ctx.info().driver_info;
  report.timestamp_mode = gpu::to_string(frame.executor.timestamp_mode());
  report.cpu_device = frame.ctx.info().is_cpu();
  report.width = frame.renderer.width();
  report.height = frame.renderer.height();
  return report;
}

// light<i>_transmittance.png: each light's map as grey levels (passes/shadows/inspection/shadow_debug_pass.h).
void write_light_images(const FrameOutputSources& frame, const fs::path& out_dir) {
  const std::vector<gpu::Image>& images = frame.renderer.light_images();
  for (size_t i = 0; i < images.size() && i < frame.scene.lights.size(); ++i)
    io::write_png_raw(out_dir / ("light" + std::to_string(i) + "_transmittance.png"),
                      gpu::read_image(frame.ctx, images[i], passes::ShadowDebugPass::kOutputLayout));
}

}  // namespace

FrameClock record_timed_frame(renderer::SceneRenderer& renderer, rg::vulkan::Executor& executor, VkCommandBuffer cmd,
                              const passes::View& view, uint32_t slot,
                              const std::function<void(VkCommandBuffer)>& also_record) {
  FrameClock clock;
  clock.start = std::chrono::steady_clock::now();
  rg::Graph graph = renderer.build_frame(view, slot);
  clock.built = std::chrono::steady_clock::now();
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
  executor.record(graph, cmd);
  if (also_record) also_record(cmd);
  VK_CHECK(vkEndCommandBuffer(cmd));
  clock.recorded = std::chrono::steady_clock::now();
  return clock;
}

FrameClock render_timed_frame(gpu::Context& ctx, renderer::SceneRenderer& renderer, rg::vulkan::Executor& executor,
                              VkCommandBuffer cmd, const passes::View& view,
                              const std::function<void(VkCommandBuffer)>& also_record) {
  FrameClock clock = record_timed_frame(renderer, executor, cmd, view, 0, also_record);
  ctx.submit_and_wait(cmd);
  clock.completed = std::chrono::steady_clock::now();
  renderer.finish_frame();
  return clock;
}

FrameTimingLog::FrameTimingLog(std::chrono::steady_clock::time_point origin) : origin_(origin) {}

double FrameTimingLog::add_frame(const FrameClock& clock, const std::vector<rg::vulkan::PassTiming>& passes,
                                 const std::vector<passes::LightShadowStats>& shadows, bool measured) {
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

  FrameSample frame;
  frame.wall_ms = wall;
  frame.submit_wall_ms = completed - recorded;
  for (const rg::vulkan::PassTiming& pass : passes) {
    if (is_shadow_stage(pass_stage(pass.name))) {
      frame.shadow_gpu_ms += pass.gpu_ms;
      frame.shadow_step_gpu_ms[std::string(shadow_step(pass.name))] += pass.gpu_ms;
    }
    if (is_inspection_pass(pass.name)) frame.inspection_gpu_ms += pass.gpu_ms;
    auto [found, added] = pass_index_.emplace(pass.name, passes_.size());
    if (added) passes_.push_back({pass.name, pass.queue, {}, {}});
    PassSamples& samples = passes_[found->second];
    samples.queue = pass.queue;
    samples.gpu_ms.push_back(pass.gpu_ms);
    samples.cpu_record_ms.push_back(pass.cpu_record_ms);
    frame.gpu_ms += pass.gpu_ms;
  }
  for (const passes::LightShadowStats& light : shadows) {
    if (!light.pages) continue;
    frame.pages_built += light.pages->built;
    frame.pages_pending += light.pages->pending;
  }
  frames_.push_back(std::move(frame));
  return wall;
}

std::map<std::string, double> FrameTimingLog::median_gpu_ms() const {
  std::map<std::string, double> medians;
  for (const PassSamples& pass : passes_)
    if (!pass.gpu_ms.empty()) medians[pass.name] = spread_of(pass.gpu_ms).median;
  return medians;
}

void FrameTimingLog::clear() { *this = FrameTimingLog(std::chrono::steady_clock::now()); }

MemoryReport memory_report(const rg::CompiledPlan& plan, const renderer::SceneRenderer& renderer,
                           const scene::Scene& scene, uint64_t frames_with_capture_overflow) {
  MemoryReport report;
  report.transient_bytes_aliased = plan.stats.transient_bytes_aliased;
  report.transient_bytes_unaliased = plan.stats.transient_bytes_unaliased;
  report.heap_count = plan.heaps.size();
  report.lights = renderer.shadows().frame_stats();
  report.scene_bounds = scene.bounds;
  report.frames_with_capture_overflow = frames_with_capture_overflow;
  report.volumes = {renderer.volume_shading(), renderer.density_atlas_bytes(), renderer.lighting_cache_cells()};
  return report;
}

FrameReport frame_report(const FrameOutputSources& frame) {
  const rg::CompiledPlan& plan = frame.executor.plan();
  return {timing_report(frame),
          memory_report(plan, frame.renderer, frame.scene, frame.frames_with_capture_overflow),
          plan_summary(plan),
          plan.to_dot(),
          std::nullopt,
          std::nullopt};
}

FrameOutputFiles write_frame_outputs(const fs::path& out_dir, const FrameOutputSources& frame) {
  std::error_code ec;
  fs::create_directories(out_dir, ec);
  if (ec) throw std::runtime_error(out_dir.string() + ": cannot create output folder: " + ec.message());

  FrameOutputFiles out{out_dir / "frame.png", out_dir / "frame.exr", out_dir / "timings.json", frame_report(frame)};
  io::write_png_raw(out.png, gpu::read_image(frame.ctx, frame.renderer.ldr(), renderer::SceneRenderer::kOutputLayout));
  io::write_exr(out.exr, gpu::read_image(frame.ctx, frame.renderer.hdr(), renderer::SceneRenderer::kOutputLayout));
  write_json(out.timings, to_json(out.report.timings));
  frame.timings.trace().write(out_dir / "trace.json");
  write_light_images(frame, out_dir);
  write_text(out_dir / "graph.json", frame.executor.plan().to_json());
  write_text(out_dir / "graph.dot", out.report.plan_dot);
  write_json(out_dir / "memory.json", to_json(out.report.memory));
  return out;
}

}  // namespace avsm::capture
