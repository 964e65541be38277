#include "capture/capture.h"

#include <algorithm>
#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <nlohmann/json.hpp>
#include <rendergraph/rendergraph.h>
#include <rendergraph/vulkan/executor.h>

#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "gpu/transfer.h"
#include "gpu/vk_check.h"
#include "io/image_io.h"
#include "passes/view.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"

namespace avsm::capture {
namespace fs = std::filesystem;

namespace {

// Timings of one pass over all measured frames.
struct PassSamples {
  std::vector<double> gpu_ms;
  std::vector<double> cpu_record_ms;
};

struct Stats {
  double min = 0, median = 0, max = 0;
};

Stats stats_of(std::vector<double> values) {
  if (values.empty()) return {};
  std::sort(values.begin(), values.end());
  return {values.front(), values[values.size() / 2], values.back()};
}

nlohmann::json to_json(const Stats& s) { return {{"min", s.min}, {"median", s.median}, {"max", s.max}}; }

const scene::Camera& pick_camera(const scene::Scene& scene, const std::string& wanted) {
  if (wanted.empty()) return scene.cameras.front();
  for (size_t i = 0; i < scene.cameras.size(); ++i)
    if (scene.cameras[i].name == wanted || std::to_string(i) == wanted) return scene.cameras[i];
  std::string names;
  for (const scene::Camera& c : scene.cameras) names += " '" + c.name + "'";
  throw std::runtime_error("scene has no camera '" + wanted + "'; cameras:" + names);
}

void write_text(const fs::path& path, const std::string& text) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  out << text;
}

void write_json(const fs::path& path, const nlohmann::json& json) {
  std::ofstream out(path);
  if (!out) throw std::runtime_error(path.string() + ": cannot write");
  out << json.dump(2) << "\n";
}

void apply_shadow_overrides(const CaptureOptions& options, scene::Scene& scene) {
  for (scene::Light& light : scene.lights) {
    scene::ShadowSettings& shadow = light.shadow;
    if (options.technique) shadow.technique = *options.technique;
    if (options.nodes) shadow.nodes = *options.nodes;
    if (options.sort) shadow.sort = *options.sort;
    if (options.filter) shadow.filter = *options.filter;
    if (options.shadow_resolution) shadow.resolution = *options.shadow_resolution;
  }
}

// A JSON array of [x, y, z] world positions.
std::vector<glm::vec3> read_probe_points(const fs::path& file) {
  std::ifstream in(file);
  if (!in) throw std::runtime_error(file.string() + ": cannot open the probe file");
  nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (json.is_discarded()) throw std::runtime_error(file.string() + ": not valid JSON");
  if (!json.is_array()) throw std::runtime_error(file.string() + ": expected an array of [x, y, z] positions");
  std::vector<glm::vec3> points;
  for (size_t i = 0; i < json.size(); ++i) {
    const nlohmann::json& p = json[i];
    if (!p.is_array() || p.size() != 3 || !p[0].is_number() || !p[1].is_number() || !p[2].is_number())
      throw std::runtime_error(file.string() + ": entry " + std::to_string(i) + " is not [x, y, z] numbers");
    points.emplace_back(p[0].get<float>(), p[1].get<float>(), p[2].get<float>());
    if (!std::isfinite(points.back().x) || !std::isfinite(points.back().y) || !std::isfinite(points.back().z))
      throw std::runtime_error(file.string() + ": entry " + std::to_string(i) + " is not finite");
  }
  return points;
}

void write_probes(const fs::path& path, const scene::Scene& scene, const std::vector<glm::vec3>& points,
                  const std::vector<std::vector<float>>& results) {
  nlohmann::json positions = nlohmann::json::array();
  for (const glm::vec3& p : points) positions.push_back({p.x, p.y, p.z});
  nlohmann::json lights = nlohmann::json::array();
  for (size_t i = 0; i < scene.lights.size() && i < results.size(); ++i) {
    const scene::ShadowSettings& s = scene.lights[i].shadow;
    lights.push_back({{"light", scene.lights[i].name},
                      {"technique", scene::to_string(s.technique)},
                      {"nodes", s.nodes},
                      {"filter", scene::to_string(s.filter)},
                      {"sort", s.sort},
                      {"resolution", s.resolution},
                      {"transmittance", results[i]}});
  }
  write_json(path, {{"points", positions}, {"lights", lights}});
}

nlohmann::json shadow_json(const passes::LightShadowStats& s) {
  return {{"light", s.light},
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
}

}  // namespace

CaptureOutputs run_capture(const CaptureOptions& options) {
  if (options.width == 0 || options.height == 0 || options.width > 16384 || options.height > 16384)
    throw std::runtime_error("image size must be between 1 and 16384 pixels per side");
  if (options.frames == 0) throw std::runtime_error("--frames must be at least 1");
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) throw std::runtime_error(options.out_dir.string() + ": cannot create output folder: " + ec.message());

  // The scene first: a bad file should fail before any device work.
  scene::Scene scene = scene::load_scene(options.scene);
  apply_shadow_overrides(options, scene);
  const std::vector<glm::vec3> probe_points =
      options.probe_file.empty() ? std::vector<glm::vec3>{} : read_probe_points(options.probe_file);
  if (options.progress)
    std::fprintf(stderr, "scene %s: %zu meshes, %zu hair grooms, %zu volumes, %zu lights\n", options.scene.c_str(),
                 scene.meshes.size(), scene.hair.size(), scene.volumes.size(), scene.lights.size());
  const scene::Camera& camera = pick_camera(scene, options.camera);

  gpu::ContextDesc desc;
  desc.app_name = "avsm-capture";
  desc.validation = options.validation;
  desc.device = options.device;
  desc.echo_validation = true;
  gpu::Context ctx(desc);
  gpu::ShaderLibrary shaders;
  gpu::TimestampCalibration calibration = gpu::calibrate_timestamps(ctx, shaders);
  if (options.progress)
    std::fprintf(stderr, "avsm-capture: %s (%s), timestamps %s\n", ctx.info().name.c_str(),
                 ctx.info().driver_info.c_str(), gpu::to_string(calibration.mode));

  passes::ShadowOptions shadow_options;
  shadow_options.exponential_interpolation = options.exponential_interpolation;
  std::unique_ptr<renderer::SceneRenderer> renderer_storage;
  try {
    renderer_storage = std::make_unique<renderer::SceneRenderer>(ctx, shaders, scene, options.width, options.height,
                                                                 shadow_options);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(options.scene.string() + ": " + e.what());
  }
  renderer::SceneRenderer& frame = *renderer_storage;
  if (!probe_points.empty()) frame.set_probes(probe_points);
  uint64_t overflowed_frames = 0;
  passes::View view = passes::make_view(camera, options.width, options.height);
  rg::vulkan::Executor executor(ctx, calibration.mode);
  VkCommandBuffer cmd = ctx.allocate_command_buffer("frame");
  std::map<std::string, PassSamples> samples;
  std::vector<std::string> pass_order;
  std::map<std::string, rg::QueueType> queues;
  std::vector<double> frame_gpu_ms, frame_wall_ms;

  for (uint32_t index = 0; index < options.frames; ++index) {
    auto start = std::chrono::steady_clock::now();
    rg::Graph graph = frame.build_frame(executor, view);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    VK_CHECK(vkBeginCommandBuffer(cmd, &begin));
    executor.record(graph, cmd);
    VK_CHECK(vkEndCommandBuffer(cmd));
    ctx.submit_and_wait(cmd);
    frame.finish_frame();
    for (const passes::LightShadowStats& light : frame.shadows().frame_stats()) {
      if (!light.overflowed) continue;
      ++overflowed_frames;
      std::fprintf(stderr,
                   "avsm-capture: warning: frame %u: light '%s' asked for %llu capture segments but had room for "
                   "%llu; the rest were dropped (lighter shadows); next frame: %llu\n",
                   index + 1, light.light.c_str(), (unsigned long long)light.capture_requested,
                   (unsigned long long)light.capture_capacity, (unsigned long long)light.next_capture_capacity);
    }
    double wall = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    bool warm_up = index == 0 && options.frames > 1;
    if (options.progress)
      std::fprintf(stderr, "frame %u/%u: %.2f ms%s\n", index + 1, options.frames, wall, warm_up ? " (warm-up)" : "");
    if (warm_up) continue;
    double total = 0;
    for (const rg::vulkan::PassTiming& pass : executor.read_timings()) {
      if (!samples.count(pass.name)) pass_order.push_back(pass.name);
      samples[pass.name].gpu_ms.push_back(pass.gpu_ms);
      samples[pass.name].cpu_record_ms.push_back(pass.cpu_record_ms);
      queues[pass.name] = pass.queue;
      total += pass.gpu_ms;
    }
    frame_gpu_ms.push_back(total);
    frame_wall_ms.push_back(wall);
  }

  CaptureOutputs out{options.out_dir / "frame.png", options.out_dir / "frame.exr", options.out_dir / "timings.json"};
  io::write_png_raw(out.png, gpu::read_image(ctx, frame.ldr(), renderer::SceneRenderer::kOutputLayout));
  io::write_exr(out.exr, gpu::read_image(ctx, frame.hdr(), renderer::SceneRenderer::kOutputLayout));

  nlohmann::json passes = nlohmann::json::array();
  for (const std::string& name : pass_order) {
    const PassSamples& s = samples[name];
    passes.push_back({{"name", name},
                      {"queue", rg::to_string(queues[name])},
                      {"gpu_ms", to_json(stats_of(s.gpu_ms))},
                      {"cpu_record_ms", to_json(stats_of(s.cpu_record_ms))}});
  }
  nlohmann::json timings = {
      {"device", ctx.info().name},
      {"driver", ctx.info().driver_name + " " + ctx.info().driver_info},
      {"timestamp_mode", gpu::to_string(calibration.mode)},
      {"width", options.width},
      {"height", options.height},
      {"frames_measured", frame_gpu_ms.size()},
      {"passes", passes},
      {"frame_gpu_ms", to_json(stats_of(frame_gpu_ms))},
      {"frame_wall_ms", to_json(stats_of(frame_wall_ms))},
  };
  write_json(out.timings, timings);
  write_text(options.out_dir / "graph.json", executor.plan().to_json());
  write_text(options.out_dir / "graph.dot", executor.plan().to_dot());
  const rg::PlanStats& stats = executor.plan().stats;
  nlohmann::json lights = nlohmann::json::array();
  for (const passes::LightShadowStats& light : frame.shadows().frame_stats()) lights.push_back(shadow_json(light));
  write_json(options.out_dir / "memory.json", {{"transient_bytes_aliased", stats.transient_bytes_aliased},
                                               {"transient_bytes_unaliased", stats.transient_bytes_unaliased},
                                               {"heaps", executor.plan().heaps.size()},
                                               {"lights", lights},
                                               {"frames_with_capture_overflow", overflowed_frames}});
  if (!probe_points.empty()) write_probes(options.out_dir / "probes.json", scene, probe_points, frame.probe_results());

  std::vector<gpu::ValidationMessage> messages = ctx.validation_log().take();
  if (!messages.empty()) throw std::runtime_error("validation reported problems: " + gpu::describe(messages));
  return out;
}

}  // namespace avsm::capture
