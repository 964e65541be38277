#include "capture/capture.h"

#include <chrono>
#include <cmath>
#include <cstdio>
#include <fstream>
#include <map>
#include <memory>
#include <optional>
#include <set>
#include <glm/gtc/matrix_transform.hpp>
#include <nlohmann/json.hpp>
#include <rendergraph/rendergraph.h>
#include <rendergraph/vulkan/executor.h>

#include "capture/files.h"
#include "capture/flicker.h"
#include "capture/frame_report.h"
#include "capture/frame_outputs.h"
#include "capture/pass_list_json.h"
#include "capture/quality.h"
#include "capture/resolution.h"
#include "capture/report.h"
#include "capture/fog_comparison.h"
#include "capture/volume_comparison.h"
#include "gpu/context.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "gpu/vk_check.h"
#include "io/image_io.h"
#include "passes/frame/view.h"
#include "passes/shadows/shadow_settings.h"
#include "renderer/frame_slots.h"
#include "renderer/scene_renderer.h"
#include "renderer/volume_sequence_player.h"
#include "scene/scene.h"

namespace avsm::capture {
namespace fs = std::filesystem;

namespace {

// Frames first..last of the scene's animation: each posed, what moved handed to the
// renderer (lights placed, meshes uploaded, the volume sequences' frames streamed), rendered
// by `render` (which returns how many renders it took), and its image written as
// frames/frame_NNNN.png. Each frame's wall time covers posing, uploading and rendering
// (and any wait for a sequence frame the reader had not finished), not the readback.
template <class Render>
void render_shot(renderer::SceneRenderer& frame, scene::Scene& scene, gpu::Context& ctx, const CaptureOptions& options,
                 ShotReport& shot, Render&& render) {
  std::optional<renderer::VolumeSequencePlayer> sequences;
  if (!scene.volume_sequences.empty()) sequences.emplace(scene.volume_sequences, ctx.info().max_image_dimension_3d);
  const std::vector<std::size_t> lights = scene.animation.moving_lights(), meshes = scene.animation.moving_meshes();
  std::error_code ec;
  fs::create_directories(options.out_dir / "frames", ec);
  if (ec) throw std::runtime_error((options.out_dir / "frames").string() + ": cannot create output folder: " + ec.message());
  for (int number = shot.range.first; number <= shot.range.last; ++number) {
    const auto start = std::chrono::steady_clock::now();
    ShotFrame& entry = shot.frames.emplace_back();  // first: the timing log reads the count (the first frame is kept apart)
    entry.frame = number;
    entry.time = shot.range.time_of(number);
    scene.animation.pose(scene, entry.time);
    for (std::size_t light : lights)
      frame.place_light(uint32_t(light), scene.lights[light].position, scene.lights[light].direction);
    for (std::size_t mesh : meshes) frame.update_mesh(uint32_t(mesh), scene.meshes[mesh]);
    if (sequences) {
      const auto waited_from = std::chrono::steady_clock::now();
      for (const renderer::VolumeSequencePlayer::Shown& shown : sequences->at(entry.time, /*wait=*/true))
        frame.show_volume_frame(shown.volume, shown.part);
      entry.volume_wait_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - waited_from).count();
    }
    entry.renders = render();
    entry.wall_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    entry.image = ShotReport::image_name(number);
    io::write_png_raw(options.out_dir / entry.image, gpu::read_image(ctx, frame.ldr(), renderer::SceneRenderer::kOutputLayout));
    entry.memory = process_memory();
    if (options.progress)
      std::fprintf(stderr, "shot frame %d (%.3f s): %.2f ms%s\n", number, double(entry.time), entry.wall_ms,
                   shot.frames.size() == 1 ? " (first: kept apart)" : "");
  }
  if (sequences) {
    const renderer::VolumeSequencePlayer::Stats stats = sequences->stats();
    shot.sequence_reading = ShotReport::SequenceReading{
        stats.frames_read, stats.waits, stats.frames_read ? stats.read_ms / double(stats.frames_read) : 0.0};
  }
}

const scene::Camera& pick_camera(const scene::Scene& scene, const std::string& wanted) {
  if (wanted.empty()) return scene.cameras.front();
  for (size_t i = 0; i < scene.cameras.size(); ++i)
    if (scene.cameras[i].name == wanted || std::to_string(i) == wanted) return scene.cameras[i];
  // A glTF file's camera by its own name, without the "<model>/" its scene name starts with.
  const scene::Camera* only = nullptr;
  for (const scene::Camera& c : scene.cameras) {
    const size_t slash = c.name.rfind('/');
    if (slash != std::string::npos && c.name.substr(slash + 1) == wanted) {
      if (only) throw std::runtime_error("camera '" + wanted + "' is ambiguous: name it with its model, as '" + c.name + "'");
      only = &c;
    }
  }
  if (only) return *only;
  std::string names;
  for (const scene::Camera& c : scene.cameras) names += " '" + c.name + "'";
  throw std::runtime_error("scene has no camera '" + wanted + "'; cameras:" + names);
}


// What the capture was made with (settings.json): `scene` as rendered (overrides applied),
// `lights` the frame's figures (the resolutions the map budget lowered).
SettingsReport settings_report(const CaptureOptions& options, const scene::Scene& scene,
                               const scene::Camera& camera, const std::vector<passes::LightShadowStats>& lights,
                               size_t probe_points) {
  SettingsReport report;
  report.scene = scene_label(options.scene);
  report.camera = camera.name.empty() ? std::to_string(&camera - scene.cameras.data()) : camera.name;
  report.width = options.width;
  report.height = options.height;
  report.frames = options.frames;
  report.frames_in_flight = options.frames_in_flight;
  report.orbit_degrees = options.orbit_degrees;
  report.light_orbit_degrees = options.light_orbit_degrees;
  report.time = options.frame_range ? std::optional(options.frame_range->time_of(options.frame_range->last)) : options.time;
  report.validation = options.validation;
  report.volume_shading = scene.volume_shading;
  report.compare_volume_shading = options.compare_volume_shading;
  report.exponential_interpolation = options.exponential_interpolation;
  report.compare_to_uncompressed = options.compare_to_uncompressed;
  report.probe_points = uint32_t(probe_points);
  for (const TexelPlot& plot : options.plot_texels) report.plot_texels.push_back(plot.spec);
  report.shadows = scene.shadows;
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const scene::Light& light = scene.lights[i];
    LightSettings settings{light.name.empty() ? "light " + std::to_string(i) : light.name, light.type, light.shadow, 0};
    if (i < lights.size() && lights[i].lowered_from != 0) settings.lowered_to = lights[i].resolution;
    report.lights.push_back(std::move(settings));
  }
  return report;
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

ProbeReport probe_report(const scene::Scene& scene, const std::vector<glm::vec3>& points,
                         const std::vector<std::vector<float>>& results) {
  ProbeReport report{points, {}};
  for (size_t i = 0; i < scene.lights.size() && i < results.size(); ++i)
    report.lights.push_back({scene.lights[i].name, scene.lights[i].shadow, results[i]});
  return report;
}

// What a completed frame lost of its shadowing (LightShadowStats::lost_shadowing), and
// whether what it lacked grew for the next frame, so that rendering again does better.
// `settling`: a paged map's requests moved its pool's LOD bias, so the next frame reads
// other levels (finer ones, once the first frame's overflow is behind it).
struct ShadowLoss {
  bool lost = false, grew = false, settling = false;
  bool building_pages = false;  // the frame built pages (under a page budget: progress)
  // Some map dropped what did not fit (capture lists, a deep shadow map's pool): lighter
  // shadows this frame. Pages still pending are not (their coarser fallback is the frame's own).
  bool dropped = false;
  // Rendering the frame again does better: what it lacked has grown, or a bias settles.
  bool worth_rendering_again() const { return (lost && grew) || settling; }
};

// What the last completed frame of `frame` lost (report_shadow_loss() also warns about it).
ShadowLoss shadow_loss(const renderer::SceneRenderer& frame) {
  ShadowLoss loss;
  for (const passes::LightShadowStats& light : frame.shadows().frame_stats()) {
    loss.settling = loss.settling || (light.pages && light.pages->settling);
    loss.building_pages = loss.building_pages || (light.pages && light.pages->built > 0);
    loss.dropped = loss.dropped || light.dropped_shadowing();
    if (!light.lost_shadowing()) continue;
    loss.lost = true;
    loss.grew = loss.grew || light.grew;
  }
  return loss;
}

// --light-orbit: every light of `scene` turned by `radians` about the vertical axis
// through the scene's centre, as placed lights (ShadowMaps::place_light: a paged map's
// pages all go stale).
void place_lights_turned(renderer::SceneRenderer& frame, const scene::Scene& scene, float radians) {
  const glm::vec3 centre = scene.bounds.center();
  const glm::mat3 turn = glm::mat3(glm::rotate(glm::mat4(1.0f), radians, glm::vec3(0.0f, 1.0f, 0.0f)));
  for (uint32_t i = 0; i < scene.lights.size(); ++i) {
    const scene::Light& light = scene.lights[i];
    frame.place_light(i, centre + turn * (light.position - centre), turn * light.direction);
  }
}

// Warns about every light whose frame lost shadowing.
ShadowLoss report_shadow_loss(const renderer::SceneRenderer& frame, uint32_t index, uint64_t& overflowed_frames) {
  for (const passes::LightShadowStats& light : frame.shadows().frame_stats()) {
    if (!light.lost_shadowing()) continue;
    if (light.page_slot_full)
      std::fprintf(stderr,
                   "avsm-capture: warning: frame %u: light '%s': a page's capture asked for %llu segments and its "
                   "slot holds %llu; the rest were dropped (lighter shadows) and the page is built again; raise "
                   "the technique's page_segments (--shadow-param page_segments=N) or the page level "
                   "(shadow.page_lod_bias)\n",
                   index + 1, light.light.c_str(), (unsigned long long)light.capture_requested,
                   (unsigned long long)light.capture_capacity);
    else if (light.overflowed)
      std::fprintf(stderr,
                   "avsm-capture: warning: frame %u: light '%s' asked for %llu capture segments but had room for "
                   "%llu; the rest were dropped (lighter shadows); next frame: %llu\n",
                   index + 1, light.light.c_str(), (unsigned long long)light.capture_requested,
                   (unsigned long long)light.capture_capacity, (unsigned long long)light.next_capture_capacity);
    if (light.dsm_pool && light.dsm_pool->overflowed)
      std::fprintf(stderr,
                   "avsm-capture: warning: frame %u: light '%s': the deep shadow map needed %llu pool nodes but had "
                   "%llu; texels that did not fit were unshadowed; %s\n",
                   index + 1, light.light.c_str(), (unsigned long long)light.dsm_pool->requested_nodes,
                   (unsigned long long)light.dsm_pool->capacity_nodes,
                   light.dsm_pool->held_by_budget ? "the map budget keeps the pool at its size (shadows.budget_mib)"
                                                  : "the pool grows for the next frame");
    if (light.dsm_pool && light.dsm_pool->build_cut_short)
      std::fprintf(stderr,
                   "avsm-capture: warning: frame %u: light '%s': the deep shadow map build needed %u dispatches but "
                   "made %u; texels whose build did not finish were unshadowed; the next frame makes %u\n",
                   index + 1, light.light.c_str(), light.dsm_pool->needed_dispatches,
                   light.dsm_pool->build_dispatches, light.dsm_pool->needed_dispatches);
  }
  const ShadowLoss loss = shadow_loss(frame);
  if (loss.lost) ++overflowed_frames;
  return loss;
}

// Why the last frame still lost shadowing when nothing could grow any more: per light, what
// did not fit or finish and the setting to change.
std::string unfinished_maps_error(const std::vector<passes::LightShadowStats>& lights, uint32_t frames_again) {
  std::string text = "the last frame's shadow maps stayed unfinished (rendered again " + std::to_string(frames_again) +
                     (frames_again == 1 ? " time" : " times") + "), so no frame was written:";
  for (const passes::LightShadowStats& light : lights) {
    if (!light.lost_shadowing()) continue;
    const std::string who = " light '" + light.light + "': ";
    if (light.page_slot_full)
      text += who + "a page's capture lists need " + std::to_string(light.capture_requested) +
              " segments and its slot holds " + std::to_string(light.capture_capacity) +
              "; raise the technique's page_segments (--shadow-param page_segments=N) and the pool "
              "(shadow.page_pool_mib), or read coarser pages (shadow.page_lod_bias);";
    else if (light.overflowed)
      text += who + "its capture lists need " + std::to_string(light.capture_requested) + " segments and may hold " +
              std::to_string(light.capture_capacity) + " (the device's storage buffer range); lower its " +
              "shadow.resolution (--shadow-res) or build its map without lists (shadow.build fixed, --build fixed);";
    if (light.dsm_pool && light.dsm_pool->overflowed)
      text += who + "its deep shadow map needs " + std::to_string(light.dsm_pool->requested_nodes) +
              " pool nodes and the map budget leaves room for " + std::to_string(light.dsm_pool->capacity_nodes) +
              "; raise the budget (shadows.budget_mib) or the dsm error (--shadow-param error=...);";
    if (light.dsm_pool && light.dsm_pool->build_cut_short)
      text += who + "its deep shadow map build needs " + std::to_string(light.dsm_pool->needed_dispatches) +
              " dispatches and the frame made " + std::to_string(light.dsm_pool->build_dispatches) + ";";
    if (light.pages && light.pages->pending > 0)
      text += who + "its receivers asked for " + std::to_string(light.pages->pending) +
              " pages it did not hold (its pool holds " + std::to_string(light.pages->slots) + " pages; " +
              std::to_string(light.pages->unserved) + " did not fit); raise shadow.page_pool_mib or " +
              "shadow.page_lod_bias;";
  }
  text.pop_back();  // the last ';'
  return text;
}

// The lights whose maps the budget made smaller (shadows.fit_budget): the capture
// says which, so that a farm run's figures are not mistaken for the asked resolution.
// One line however many lights: per change of resolution, its first few lights and a
// count of the rest (memory.json's lowered_from has every light).
void report_lowered_resolutions(const renderer::SceneRenderer& frame, const scene::Scene& scene) {
  constexpr size_t kNamed = 4;
  const passes::ShadowMaps& shadows = frame.shadows();
  std::map<std::pair<int, uint32_t>, std::vector<std::string>> lowered;  // (asked, got) -> light names
  for (uint32_t i = 0; i < shadows.light_count() && i < scene.lights.size(); ++i) {
    if (scene.lights[i].shadow.layout == scene::ShadowLayout::paged) continue;  // never lowered: its pool is fixed
    const int asked = scene.lights[i].shadow.resolution;
    const uint32_t got = shadows.map_layout(i).resolution;
    if (got < uint32_t(asked)) lowered[{asked, got}].push_back(scene.lights[i].name);
  }
  if (lowered.empty()) return;
  std::string text;
  for (const auto& [change, names] : lowered) {
    text += text.empty() ? "" : "; ";
    text += names.size() == 1 ? "light" : std::to_string(names.size()) + " lights";
    for (size_t n = 0; n < names.size() && n < kNamed; ++n) text += (n ? ", '" : " '") + names[n] + "'";
    if (names.size() > kNamed) text += " and " + std::to_string(names.size() - kNamed) + " more";
    text += " from " + std::to_string(change.first) + " to " + std::to_string(change.second);
  }
  std::fprintf(stderr,
               "avsm-capture: warning: shadow resolution lowered to fit the map budget (shadows.budget_mib): %s\n",
               text.c_str());
}

// The fixed build keeps one blocker per light texel, so a blended (alphaMode BLEND)
// caster cannot be translucent there: it blocks only where its alpha is 1 and lets all
// light through elsewhere (passes/shadows/fixed_build/light_depth_pass.h). Says so for every light built
// that way while the scene has such casters; the lists build casts them translucently.
void report_blend_casters_in_fixed_builds(const scene::Scene& scene) {
  std::set<std::string> blended;
  for (const scene::Mesh& mesh : scene.meshes)
    if (mesh.material < scene.materials.size() && scene.materials[mesh.material].alpha_mode == scene::AlphaMode::blend)
      blended.insert("'" + scene.materials[mesh.material].name + "'");
  if (blended.empty()) return;
  std::string names;
  for (const std::string& name : blended) names += (names.empty() ? "" : ", ") + name;
  for (const scene::Light& light : scene.lights)
    if (light.shadow.build == scene::ShadowBuild::fixed)
      std::fprintf(stderr,
                   "avsm-capture: warning: light '%s' builds its map in fixed memory (shadow.build \"fixed\"), "
                   "where blended materials (alphaMode BLEND: %s) cast no shadow except where their alpha is 1; "
                   "shadow.build \"lists\" casts them as translucent occluders\n",
                   light.name.c_str(), names.c_str());
}

std::string describe(const scene::VolumeShading& shading) {
  return std::string(scene::to_string(shading.mode)) + ", resolution divisor " +
         std::to_string(shading.resolution_divisor) + ", step " + std::to_string(shading.step_voxels) + " voxels";
}

// Images of one size next to each other, left to right.
gpu::ImageRGBA32F side_by_side(std::initializer_list<const gpu::ImageRGBA32F*> images) {
  const gpu::ImageRGBA32F& first = **images.begin();
  gpu::ImageRGBA32F out{first.width * uint32_t(images.size()), first.height, {}};
  out.pixels.reserve(size_t(out.width) * out.height * 4);
  for (uint32_t y = 0; y < first.height; ++y)
    for (const gpu::ImageRGBA32F* image : images)
      out.pixels.insert(out.pixels.end(), image->pixels.begin() + ptrdiff_t(y) * image->width * 4,
                        image->pixels.begin() + ptrdiff_t(y + 1) * image->width * 4);
  return out;
}

// --compare-fog, after the main frames: the last view again with the fog marched per pixel
// and without fog, measured against the last main frame (capture/fog_comparison.h).
fs::path compare_fog_frames(gpu::Context& ctx, renderer::SceneRenderer& frame, gpu::TimestampMode mode,
                            const passes::View& view, const fs::path& out_dir) {
  const gpu::ImageRGBA32F fast = gpu::read_image(ctx, frame.hdr(), renderer::SceneRenderer::kOutputLayout);
  rg::vulkan::Executor executor(ctx, mode);
  VkCommandBuffer cmd = ctx.allocate_command_buffer("fog comparison frame");
  auto render = [&] {
    render_timed_frame(ctx, frame, executor, cmd, view);
    return gpu::read_image(ctx, frame.hdr(), renderer::SceneRenderer::kOutputLayout);
  };
  frame.set_fog_marched_per_pixel(true);
  const gpu::ImageRGBA32F reference = render();
  frame.set_fog_marched_per_pixel(std::nullopt);
  frame.set_fog_enabled(false);
  const gpu::ImageRGBA32F without_fog = render();
  frame.set_fog_enabled(true);
  io::write_exr(out_dir / "frame_fog_reference.exr", reference);
  const fs::path file = out_dir / "fog_quality.json";
  write_fog_comparison(file, compare_fog(fast, reference, without_fog));
  return file;
}

// The reference and hidden-volume frames of --compare-volume-shading, each timed on
// its own executor (their graphs differ from the main frame's).
class VolumeShadingRun {
 public:
  VolumeShadingRun(gpu::Context& ctx, gpu::TimestampMode mode, renderer::SceneRenderer& frame,
                   const scene::Scene& scene, int path_traced_paths)
      : ctx_(ctx), frame_(frame), scene_(scene), paths_(path_traced_paths), main_(frame.volume_shading()),
        executor_(ctx, mode) {}

  // One reference frame, timed beside the main frames.
  void render_reference(VkCommandBuffer cmd, const passes::View& view, bool measured) {
    render_as(scene::VolumeShading::Mode::reference, cmd, view, measured, nullptr);
  }
  // After the last main frame was written: the reference and hidden frames the comparison
  // reads, and the comparison files.
  fs::path finish(const fs::path& out_dir, VkCommandBuffer cmd, const passes::View& view,
                  const FrameTimingLog& main_log) {
    const gpu::ImageRGBA32F fast = gpu::read_image(ctx_, frame_.hdr(), renderer::SceneRenderer::kOutputLayout);
    gpu::ImageRGBA32F hidden, error;
    FrameTimingLog unused;
    // The reference marches the smoke where the fast frame's lighting cache does not, so a
    // paged map may lack pages it asks for: rendered again until its maps are finished.
    for (uint32_t again = 0; again < kMaxReferenceFrames; ++again) {
      render_as(scene::VolumeShading::Mode::reference, cmd, view, false, &reference_, &unused);
      if (!shadow_loss(frame_).worth_rendering_again()) break;
    }
    render_as(scene::VolumeShading::Mode::hidden, cmd, view, false, &hidden, &unused);
    const VolumeShadingComparison comparison = compare_volume_shading(fast, reference_, hidden, &error);
    io::write_png_raw(out_dir / "volume_error.png", error);
    io::write_exr(out_dir / "frame_reference.exr", reference_);
    std::optional<PathTracedComparison> traced;
    if (paths_ > 0) {
      const gpu::ImageRGBA32F path_traced = path_trace_volumes(scene_, view, hidden, paths_);
      io::write_exr(out_dir / "frame_path_traced.exr", path_traced);
      io::write_png_srgb(out_dir / "volume_path_traced.png", side_by_side({&fast, &reference_, &path_traced}));
      traced = compare_with_path_traced(fast, reference_, hidden, path_traced, paths_);
    }
    const fs::path file = out_dir / "volume_quality.json";
    write_volume_comparison(file, comparison, describe(main_), main_log.median_gpu_ms(), log_.median_gpu_ms(),
                            traced ? &*traced : nullptr);
    return file;
  }

 private:
  static constexpr uint32_t kMaxReferenceFrames = 16;

  void render_as(scene::VolumeShading::Mode mode, VkCommandBuffer cmd, const passes::View& view, bool measured,
                 gpu::ImageRGBA32F* keep, FrameTimingLog* log = nullptr) {
    scene::VolumeShading shading = main_;
    shading.mode = mode;
    frame_.set_volume_shading(shading);
    // The hidden frame is the reference's twin without smoke: its hair is lit per fragment too.
    const std::optional<bool> hair_per_fragment = frame_.hair_lighting_per_fragment();
    if (mode == scene::VolumeShading::Mode::hidden) frame_.set_hair_lighting_per_fragment(true);
    const FrameClock clock = render_timed_frame(ctx_, frame_, executor_, cmd, view);
    (log ? *log : log_).add_frame(clock, executor_.read_timings(), frame_.shadows().frame_stats(), measured);
    if (keep) *keep = gpu::read_image(ctx_, frame_.hdr(), renderer::SceneRenderer::kOutputLayout);
    frame_.set_hair_lighting_per_fragment(hair_per_fragment);
    frame_.set_volume_shading(main_);
  }

  gpu::Context& ctx_;
  renderer::SceneRenderer& frame_;
  const scene::Scene& scene_;
  int paths_ = 0;
  scene::VolumeShading main_;
  rg::vulkan::Executor executor_;
  FrameTimingLog log_;
  gpu::ImageRGBA32F reference_;
};

}  // namespace

CaptureOutputs run_capture(const CaptureOptions& options) {
  // The largest size is the device's (its image dimension limit and memory, checked as the
  // targets are made: gpu/device_limits.h).
  if (options.width == 0 || options.height == 0)
    throw std::runtime_error("image size must be at least 1 pixel per side");
  if (options.frames == 0) throw std::runtime_error("--frames must be at least 1");
  try {
    passes::check_frames_in_flight(options.frames_in_flight);
  } catch (const std::invalid_argument& e) {
    throw std::runtime_error(e.what());
  }
  std::error_code ec;
  fs::create_directories(options.out_dir, ec);
  if (ec) throw std::runtime_error(options.out_dir.string() + ": cannot create output folder: " + ec.message());

  // The scene first: a bad file should fail before any device work.
  scene::Scene scene = scene::load_scene(options.scene);
  for (scene::Light& light : scene.lights) passes::apply_shadow_overrides(options.shadow, light);
  // The instant rendered (a shot's first frame's): the renderer is made with the scene there.
  const std::optional<float> first_time = options.frame_range ? options.frame_range->time_of(options.frame_range->first) : options.time;
  if (first_time) {
    if (!scene.moves())
      std::fprintf(stderr, "avsm-capture: warning: %s: the scene has no animation; nothing moves\n",
                   options.frame_range ? "--frame-range" : "--time");
    scene.animation.pose(scene, *first_time);
    for (const scene::VolumeSequence& sequence : scene.volume_sequences)
      scene.volumes[sequence.volume] = sequence.load_frame(sequence.timing.frame_at(*first_time));
  }
  options.volume_shading.apply(scene.volume_shading);
  for (scene::Volume& volume : scene.volumes) {
    if (options.volume_octaves) volume.multiple_scattering.octaves = *options.volume_octaves;
    if (options.volume_sky_light) volume.sky_light = *options.volume_sky_light;
  }
  const std::vector<glm::vec3> probe_points =
      options.probe_file.empty() ? std::vector<glm::vec3>{} : read_probe_points(options.probe_file);
  std::vector<TexelPlot> plots = options.plot_texels;
  resolve_texel_plots(plots, scene);
  if (options.progress)
    std::fprintf(stderr, "scene %s: %zu meshes, %zu hair grooms, %zu volumes, %zu lights\n", options.scene.c_str(),
                 scene.meshes.size(), scene.hair.size(), scene.volumes.size(), scene.lights.size());
  for (const std::string& warning : scene.warnings)  // what loaded but is not rendered as the file says
    std::fprintf(stderr, "avsm-capture: warning: %s\n", warning.c_str());
  const scene::Camera& camera = pick_camera(scene, options.camera);

  gpu::ContextDesc desc;
  desc.app_name = "avsm-capture";
  desc.validation = options.validation;
  desc.device = options.device;
  desc.echo_validation = true;
  gpu::Context ctx(desc);
  gpu::ShaderLibrary shaders;
  if (options.progress)
    std::fprintf(stderr, "avsm-capture: %s (%s)\n", ctx.info().name.c_str(), ctx.info().driver_info.c_str());

  passes::ShadowOptions shadow_options;
  shadow_options.exponential_interpolation = options.exponential_interpolation;
  // The quality figures and texel curves compare against each light's exact lists.
  shadow_options.keep_reference = options.compare_to_uncompressed || !plots.empty();
  shadow_options.keep_paged_reference = shadow_options.keep_reference;  // pages of lists, read on the GPU
  // A capture writes converged paged maps only: it builds every page asked for at once,
  // or with --page-builds at most that many a frame, rendering again until none is pending.
  const bool page_budget = options.shadow.page_builds_per_frame.value_or(0) > 0;
  shadow_options.unlimited_page_builds = !page_budget;
  std::unique_ptr<renderer::SceneRenderer> renderer_storage;
  try {
    renderer_storage = std::make_unique<renderer::SceneRenderer>(ctx, shaders, scene, options.width, options.height,
                                                                 shadow_options);
  } catch (const std::invalid_argument& e) {
    // The shadow settings' checks already name the scene file (ShadowMaps::set_scene).
    const std::string prefix = options.scene.string() + ": ", what = e.what();
    throw std::runtime_error(what.starts_with(prefix) ? what : prefix + what);
  }
  renderer::SceneRenderer& frame = *renderer_storage;
  frame.set_frames_in_flight(options.frames_in_flight);
  if (options.fog) frame.set_fog_enabled(*options.fog);
  frame.set_area_shadows_filtered(options.area_shadows_filtered);
  if (options.compare_fog && !frame.fog_enabled())
    throw std::runtime_error(options.scene.string() + ": --compare-fog needs fog, and the scene has none (add a \"fog\" block)");
  report_lowered_resolutions(frame, scene);
  report_blend_casters_in_fixed_builds(scene);
  if (!probe_points.empty()) frame.set_probes(probe_points);
  if (options.compare_to_uncompressed) frame.enable_quality();
  if (options.measure_resolution) frame.enable_resolution_figures();
  if (!plots.empty()) frame.set_texel_samples(texel_curve_samples(plots, frame.shadows().light_views()));
  // Frame `index`'s view: the camera turned by --orbit per frame; frames rendered again
  // keep the last frame's.
  auto view_of = [&](uint32_t index) {
    const float degrees = options.orbit_degrees * float(std::min(index, options.frames - 1));
    return passes::make_view(scene::orbited(camera, glm::radians(degrees)), options.width, options.height);
  };
  // --flicker: fixed surface points, looked up every frame.
  std::optional<FlickerMeter> flicker;
  if (options.flicker) {
    if (!scene.animation.lights.empty() || !scene.animation.models.empty() || !scene.volume_sequences.empty())
      throw std::runtime_error("--flicker needs a scene where only the camera moves: its lights, models or volume "
                               "sequences move, and their exact shadows with them");
    const FlickerProbes probes = flicker_probes(scene, view_of(0), 64, 36);
    if (probes.points.empty()) throw std::runtime_error("--flicker: the first frame shows no surface to measure at");
    frame.set_surface_probes(probes.points, probes.normals);
    std::vector<std::string> names;
    for (const scene::Light& light : scene.lights) names.push_back(light.name);
    flicker.emplace(names, light_shares(scene));
  }
  if (!options.dump_passes.empty()) {  // the first frame's shadow work, described only
    write_pass_list(options.dump_passes, frame.describe_shadows(view_of(0)));
    std::vector<gpu::ValidationMessage> messages = ctx.validation_log().take();
    if (!messages.empty()) throw std::runtime_error("validation reported problems: " + gpu::describe(messages));
    CaptureOutputs out;
    out.pass_list = options.dump_passes;
    return out;
  }
  gpu::TimestampCalibration calibration = gpu::calibrate_timestamps(ctx, shaders);
  if (options.progress) std::fprintf(stderr, "avsm-capture: timestamps %s\n", gpu::to_string(calibration.mode));
  frame.enable_light_images();
  uint64_t overflowed_frames = 0;
  renderer::FrameSlots slots(ctx, calibration.mode, options.frames_in_flight);
  FrameTimingLog timing_log;
  // Frames rendered again at most while a map is unfinished (each grows what it lacked);
  // under a page budget, while pages asked for are still being built.
  constexpr uint32_t kMaxFramesAgain = 8, kMaxFramesBuildingPages = 512;

  // What each slot's frame in flight is: its number and clock.
  std::vector<uint32_t> slot_frame(slots.count());
  std::vector<FrameClock> slot_clock(slots.count());
  std::vector<std::chrono::steady_clock::time_point> completed;  // per frame finished
  ShadowLoss last_loss;
  std::optional<ShotReport> shot;
  if (options.frame_range) shot = ShotReport{*options.frame_range, {}};
  // A frame's figures, when its fence signalled (frames finish in order).
  auto finished = [&](renderer::FrameSlots::Slot& slot) {
    FrameClock& clock = slot_clock[slot.index];
    clock.completed = std::chrono::steady_clock::now();
    completed.push_back(clock.completed);
    frame.finish_frame(slot.index);
    const uint32_t index = slot_frame[slot.index];
    last_loss = report_shadow_loss(frame, std::min(index, options.frames - 1), overflowed_frames);
    if (flicker && !shot && index < options.frames) flicker->add_frame(frame.probe_results(), last_loss.dropped);
    // Left out of the timings: the first of repeated frames, or a shot's first frame.
    const bool warm_up = shot ? shot->frames.size() == 1 : index == 0 && options.frames > 1;
    const double wall = timing_log.add_frame(clock, slot.executor->read_timings(), frame.shadows().frame_stats(),
                                             /*measured=*/!warm_up);
    if (options.progress && !shot)
      std::fprintf(stderr, "frame %u/%u: %.2f ms%s\n", std::min(index, options.frames - 1) + 1, options.frames, wall,
                   warm_up ? " (warm-up)" : index >= options.frames ? " (again)" : "");
  };
  // Records frame `index` into the next slot (first finishing the frame it held) and submits it.
  auto submit_frame = [&](uint32_t index) {
    renderer::FrameSlots::Slot& slot = slots.acquire(finished);
    if (options.light_orbit_degrees != 0.0f && index > 0 && index < options.frames)
      place_lights_turned(frame, scene, glm::radians(options.light_orbit_degrees * float(index)));
    slot_frame[slot.index] = index;
    slot_clock[slot.index] = record_timed_frame(frame, *slot.executor, slot.cmd, view_of(index), slot.index);
    slots.submit(slot);
  };
  std::optional<VolumeShadingRun> volume_run;
  if (options.compare_volume_shading) volume_run.emplace(ctx, calibration.mode, frame, scene, options.path_trace_volumes);
  VkCommandBuffer comparison_cmd = volume_run ? ctx.allocate_command_buffer("volume comparison frame") : VK_NULL_HANDLE;

  // A frame whose maps are unfinished (capture lists or a deep shadow map's pool too
  // small, or its build cut short) is never written. What it lacked grew for the frames
  // after it, so the last frame is rendered again until its maps are finished, while
  // something still grows; if they never are, the capture fails naming the lights.
  // A paged map's bias settling is waited for too (it only makes the frame finer), but a
  // frame written while it still moves is not an error. Returns how often it rendered again.
  const auto render_again_while_unfinished = [&] {
    uint32_t frames_again = 0;
    const auto may_render_again = [&] {
      const bool building_pages = page_budget && last_loss.building_pages;
      return frames_again < (building_pages ? kMaxFramesBuildingPages : kMaxFramesAgain);
    };
    for (; last_loss.worth_rendering_again() && may_render_again(); ++frames_again) {
      if (options.progress)
        std::fprintf(stderr, "frame %u: shadow maps unfinished (buffers grown, pages asked for, a page bias settling): rendering it again\n",
                     options.frames);
      submit_frame(options.frames + frames_again);
      slots.finish_all(finished);
    }
    if (last_loss.lost) throw std::runtime_error(unfinished_maps_error(frame.shadows().frame_stats(), frames_again));
    return frames_again;
  };

  const auto loop_start = std::chrono::steady_clock::now();
  if (shot) render_shot(frame, scene, ctx, options, *shot, [&] {
    submit_frame(options.frames - 1);
    slots.finish_all(finished);
    const uint32_t renders = 1 + render_again_while_unfinished();
    if (flicker) flicker->add_frame(frame.probe_results());  // the frame as written
    return renders;
  });
  for (uint32_t index = 0; !shot && index < options.frames; ++index) {
    // Interleaved with the main frames, so both paths see the same machine load; it
    // renders with nothing else in flight.
    if (volume_run) {
      slots.finish_all(finished);
      volume_run->render_reference(comparison_cmd, view_of(index), /*measured=*/index > 0 || options.frames == 1);
    }
    submit_frame(index);
  }
  slots.finish_all(finished);
  const double loop_ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - loop_start).count();
  if (options.progress && completed.size() > 1)
    std::fprintf(stderr, "avsm-capture: %zu frames in %.1f ms (%u in flight): %.2f ms per frame after the first\n",
                 completed.size(), loop_ms, slots.count(),
                 std::chrono::duration<double, std::milli>(completed.back() - completed.front()).count() /
                     double(completed.size() - 1));
  if (!shot) render_again_while_unfinished();
  const rg::vulkan::Executor& executor = slots.last_finished_executor();

  FrameOutputFiles files = write_frame_outputs(options.out_dir,
                                               {ctx, frame, executor, scene, timing_log, overflowed_frames});
  FrameReport& report = files.report;
  CaptureOutputs out{files.png, files.exr, files.timings};
  if (shot) {
    write_shot_video(options.out_dir, *shot);
    if (options.progress)
      std::fprintf(stderr, "video:   %s\n", shot->video.empty() ? shot->video_note.c_str() : (options.out_dir / shot->video).c_str());
    out.shot = options.out_dir / "shot.json";
    write_json(out.shot, to_json(*shot));
    report.shot = shot;
  }
  if (flicker) {
    const FlickerReport figures = flicker->report();
    write_json(options.out_dir / "flicker.json", to_json(figures));
    if (options.progress)
      std::fprintf(stderr, "flicker: mean dL %.5f over %u points and %u frame pairs (%u unfinished frames left out)\n",
                   figures.mean_delta_l, figures.points, figures.frame_pairs, figures.unfinished_frames);
  }
  if (!probe_points.empty()) {
    report.probes = probe_report(scene, probe_points, frame.probe_results());
    write_json(options.out_dir / "probes.json", to_json(*report.probes));
  }
  if (options.compare_to_uncompressed) {
    report.quality = write_quality(options.out_dir, scene, frame.quality_results(), options.width, options.height,
                                   {frame.hair_quality_results(), frame.hair_receiver_count()});
    out.quality = options.out_dir / "quality.json";
  }
  if (options.measure_resolution) {
    report.resolution = write_resolution(options.out_dir, scene, frame.resolution_results(), options.width,
                                         options.height);
    out.resolution = options.out_dir / "resolution.json";
  }
  if (volume_run) out.volume_quality = volume_run->finish(options.out_dir, comparison_cmd, view_of(options.frames - 1), timing_log);
  if (options.compare_fog) out.fog_quality = compare_fog_frames(ctx, frame, calibration.mode, view_of(options.frames - 1), options.out_dir);
  if (!plots.empty())
    out.curves = write_texel_curves(options.out_dir, plots, scene, frame.shadows(), ctx, frame.texel_results());
  report.settings = settings_report(options, scene, camera, report.memory.lights, probe_points.size());
  write_json(options.out_dir / "settings.json", to_json(*report.settings));
  if (options.report) write_report(options.out_dir, report, options.out_dir / "report.html");

  std::vector<gpu::ValidationMessage> messages = ctx.validation_log().take();
  if (!messages.empty()) throw std::runtime_error("validation reported problems: " + gpu::describe(messages));
  return out;
}

}  // namespace avsm::capture
