#include "viewer/viewer_app.h"

#define GLFW_INCLUDE_NONE
#include <GLFW/glfw3.h>
#include <imgui.h>
#include <rendergraph/vulkan/executor.h>
#include <rendergraph/vulkan/pass_context.h>

#include <malloc.h>

#include <algorithm>
#include <chrono>
#include <cstdio>
#include <fstream>
#include <iostream>
#include <memory>
#include <thread>
#include <nlohmann/json.hpp>

#include "capture/frame_outputs.h"
#include "gpu/context.h"
#include "gpu/gpu_timer.h"
#include "gpu/shader_compiler.h"
#include "gpu/vk_check.h"
#include "io/image_io.h"
#include "live/live_renderer.h"
#include "renderer/frame_slots.h"
#include "viewer/camera_controller.h"
#include "viewer/control_commands.h"
#include "viewer/imgui_renderer.h"
#include "viewer/light_map_textures.h"
#include "viewer/panel.h"
#include "viewer/timeline.h"
#include "viewer/swapchain.h"
#include "viewer/texel_inspector.h"
#include "viewer/view_layout.h"
#include "viewer/window.h"

namespace avsm::viewer {
namespace fs = std::filesystem;

namespace {

using Clock = std::chrono::steady_clock;

// A click is a press and release that moved less than this (pixels squared); more is a drag.
constexpr float kClickSlopSquared = 9.0f;
// How long an idle loop sleeps waiting for input before it polls the files again.
constexpr double kIdleWaitSeconds = 0.1;

gpu::ContextDesc context_desc(const ViewerOptions& options, const Window& window) {
  gpu::ContextDesc desc;
  desc.app_name = "avsm-viewer";
  desc.validation = options.validation;
  desc.device = options.device;
  desc.echo_validation = true;
  desc.instance_extensions = window.required_instance_extensions();
  desc.device_extensions = {VK_KHR_SWAPCHAIN_EXTENSION_NAME};
  return desc;
}

// The first folder out_dir/shot-NNN that does not exist yet.
fs::path next_shot_dir(const fs::path& out_dir) {
  for (int n = 1;; ++n) {
    char name[32];
    std::snprintf(name, sizeof(name), "shot-%03d", n);
    if (!fs::exists(out_dir / name)) return out_dir / name;
  }
}

void write_rgba_png(const fs::path& path, const std::vector<uint8_t>& rgba, VkExtent2D extent) {
  gpu::ImageRGBA32F image;
  image.width = extent.width;
  image.height = extent.height;
  image.pixels.resize(rgba.size());
  for (size_t i = 0; i < rgba.size(); ++i) image.pixels[i] = float(rgba[i]) / 255.0f;
  io::write_png_raw(path, image);
}

VkImageSubresourceRange colour_range() { return {VK_IMAGE_ASPECT_COLOR_BIT, 0, 1, 0, 1}; }

class ViewerApp {
 public:
  explicit ViewerApp(const ViewerOptions& options);
  int run();

 private:
  // One loop iteration: input, watched files, panel, a scene frame when something
  // changed (or `render`), present.
  void iterate(bool render);
  int run_controlled();
  nlohmann::json execute(const ControlCommand& command);
  // One loop iteration's parts.
  void follow_window_size();
  void poll_live();
  // Polls until no edited file is still settling (live/file_watcher.h), so that a
  // control script's "frame" after its edits shows them.
  void wait_for_settled_files();
  void handle_input();
  // Plays the scene's animation: interactively by the wall clock; under --control one
  // frame of the timeline per rendered frame, so that a script's frames are a shot's.
  void advance_timeline(bool render);
  void show_time();  // hands the timeline's time to the live renderer
  void apply(const PanelRequests& requests);
  // Records and submits a scene frame; its results are read when it completes.
  void render_scene_frame();
  void scene_frame_finished(renderer::FrameSlots::Slot& slot);
  // Waits for the scene frames in flight and reads their results (before the renderer
  // changes, and before anything reads the last frame's outputs).
  void finish_scene_frames();
  void present(const ImDrawData& draw_data);
  void record_window(renderer::FrameSlots::Slot& slot, uint32_t image, const ImDrawData& draw_data, bool read_back);
  // The window graph's passes; each returns the swapchain image's new version.
  rg::TextureHandle add_scene_blit(rg::Graph& graph, rg::TextureHandle target);
  rg::TextureHandle add_grey_clear(rg::Graph& graph, rg::TextureHandle target);
  rg::TextureHandle add_panel(rg::Graph& graph, rg::TextureHandle target, const ImDrawData& draw_data, uint32_t slot);
  void add_window_readback(rg::Graph& graph, rg::TextureHandle target, uint32_t image);
  void write_screenshot(const fs::path& dir, const std::vector<uint8_t>& window_rgba);
  void write_layout(const fs::path& path) const;

  // `pixel`: in the view's image (x right, y down from its top-left pixel).
  void inspect_pixel(glm::vec2 pixel);
  void refresh_inspection();
  void ensure_reference();
  passes::View current_view();
  void set_status(const std::string& text);
  int finish();

  ViewerOptions options_;
  Window window_;
  gpu::Context ctx_;
  Surface surface_;
  Swapchain swapchain_;
  // The panel's column and the 3D view beside it (view_layout.h), for the swapchain's
  // extent; the scene renders at the view's size.
  ViewLayout layout_;
  gpu::ShaderLibrary builtin_shaders_;  // prebuilt SPIR-V: timestamp calibration and the panel
  gpu::TimestampCalibration calibration_;
  ImGuiWindowInput imgui_input_;
  ImGuiRenderer imgui_renderer_;
  ViewerSettings settings_;
  std::unique_ptr<live::LiveRenderer> live_;
  // Frames in flight: scene frames (when something changed) and window frames (every
  // iteration) each go round their own slots; a slot is reused once its frame completed.
  renderer::FrameSlots scene_slots_;
  renderer::FrameSlots window_slots_;  // the window composite (record_window)
  std::vector<capture::FrameClock> scene_clocks_;  // per scene slot: its frame's clock
  uint64_t frames_submitted_ = 0;                  // scene frames; frame_stats_.number counts the finished
  CameraController camera_;
  Panel panel_;
  TexelInspector inspector_;
  LightMapTextures light_maps_;
  std::vector<ImTextureID> light_map_ids_;
  FrameStats frame_stats_;
  capture::FrameTimingLog timing_log_;
  uint64_t overflowed_frames_ = 0;
  gpu::Buffer window_readback_;

  bool scene_dirty_ = true;     // the next iteration renders a scene frame
  bool edits_pending_ = false;  // the live renderer applies edits on its next poll: render after it
  bool ldr_valid_ = false;      // the renderer's ldr() holds a frame of the current size
  std::optional<fs::path> screenshot_dir_;  // written at the next present
  fs::path scene_file_;
  std::string status_;
  Clock::time_point last_iteration_ = Clock::now();
  Timeline timeline_;
  Clock::time_point last_tick_ = Clock::now();
  bool failed_ = false;
  // What poll() reported since the last control reply.
  std::vector<std::string> reloaded_files_;
  bool files_settling_ = false;  // the last poll saw a change still being written
  bool shaders_reloaded_ = false, scene_reloaded_ = false;
};

// The scene renders at the view's size; a minimised window's empty view renders at 1x1
// until the window has a size again.
live::LiveOptions live_options(const ViewerOptions& options, const PixelRect& view, const passes::ShadowOptions& shadows) {
  live::LiveOptions live;
  live.scene_file = options.scene;
  live.width = std::max(view.width, 1u);
  live.height = std::max(view.height, 1u);
  live.shadow_options = shadows;
  return live;
}

ViewerApp::ViewerApp(const ViewerOptions& options)
    : options_(options),
      window_("avsm-viewer", options.width, options.height),
      ctx_(context_desc(options, window_)),
      surface_(ctx_.instance(), window_),
      swapchain_(ctx_, surface_.handle(), window_.framebuffer_size(), options.frames_in_flight),
      layout_(layout_for({swapchain_.extent().width, swapchain_.extent().height}, window_.framebuffer_scale())),
      calibration_(gpu::calibrate_timestamps(ctx_, builtin_shaders_)),
      imgui_input_(window_),
      imgui_renderer_(ctx_, builtin_shaders_, swapchain_.format()),
      settings_{.overrides = {.volume_shading = options.volume_shading},
                .shadow_options = {.keep_reference = options.inspect_pixel.has_value()}},
      live_(std::make_unique<live::LiveRenderer>(
          ctx_, live_options(options, layout_.view, settings_.shadow_options))),
      scene_slots_(ctx_, calibration_.mode, options.frames_in_flight),
      window_slots_(ctx_, calibration_.mode, options.frames_in_flight),
      scene_clocks_(options.frames_in_flight),
      camera_(live_->scene().cameras.front()),
      panel_(options.scene.string()),
      light_maps_(ctx_, calibration_.mode),
      scene_file_(options.scene) {
  // Every renderer the live renderer builds (a shader reload builds a new one) gets
  // the viewer's exposure and light pictures.
  // The volume-shading flags reach the renderer as a scene edit, like the panel's.
  live_->set_scene_edit([overrides = settings_.overrides](scene::Scene& scene) { overrides.apply(scene); });
  live_->set_renderer_setup([this](renderer::SceneRenderer& renderer) {
    renderer.set_frames_in_flight(options_.frames_in_flight);
    renderer.set_exposure(settings_.exposure);
    renderer.enable_light_images();
    if (settings_.level_overlay && *settings_.level_overlay >= renderer.shadows().light_count())
      settings_.level_overlay.reset();  // a reloaded scene with fewer lights
    renderer.set_level_overlay(settings_.level_overlay);
  });
  live_->set_before_change([this] { finish_scene_frames(); });
  std::fprintf(stderr, "avsm-viewer: %s (%s), %ux%u, view %ux%u beside a %u px panel, scene %s, %u frames in flight\n",
               ctx_.info().name.c_str(), ctx_.info().driver_info.c_str(), swapchain_.extent().width,
               swapchain_.extent().height, layout_.view.width, layout_.view.height, layout_.panel.width,
               options.scene.c_str(), options.frames_in_flight);
  if (options.inspect_pixel) inspect_pixel(*options.inspect_pixel);
}

int ViewerApp::run() {
  if (options_.control) return run_controlled();
  const bool scripted = options_.frames > 0;
  while (!window_.should_close() && !failed_ && !(scripted && frames_submitted_ >= options_.frames))
    iterate(/*render=*/scripted);
  finish_scene_frames();
  if (scripted && !options_.screenshot_dir.empty() && !failed_) {
    // One more present, of the last frame with the panel showing its timings.
    screenshot_dir_ = options_.screenshot_dir;
    iterate(/*render=*/false);
  }
  return finish();
}

void ViewerApp::iterate(bool render) {
  window_.poll_events(render || scene_dirty_ || edits_pending_ || timeline_.playing() ? 0.0 : kIdleWaitSeconds);
  follow_window_size();
  poll_live();
  advance_timeline(render);
  scene_slots_.finish_completed([this](renderer::FrameSlots::Slot& slot) { scene_frame_finished(slot); });

  imgui_input_.new_frame();
  handle_input();
  apply(panel_.draw({*live_, scene_slots_.last_finished_executor().plan(), frame_stats_, inspector_, light_map_ids_, camera_.mode, status_,
                     timeline_},
                    settings_, layout_));
  ImGui::Render();
  // Edits waiting for the next poll would make this frame stale: render after it.
  if ((scene_dirty_ || render) && !edits_pending_ && !layout_.view.empty()) render_scene_frame();
  present(*ImGui::GetDrawData());
}

int ViewerApp::run_controlled() {
  std::string line;
  while (!failed_ && std::getline(std::cin, line)) {
    if (line.empty()) continue;
    nlohmann::json reply;
    bool quit = false;
    try {
      const ControlCommand command = parse_control_command(line);
      quit = command.kind == ControlCommand::Kind::quit;
      reply = execute(command);
      reply["command"] = line;
    } catch (const std::invalid_argument& e) {
      reply = {{"command", line}, {"rejected", e.what()}};
    }
    std::cout << reply.dump() << std::endl;
    if (quit) break;
  }
  return finish();
}

nlohmann::json ViewerApp::execute(const ControlCommand& command) {
  nlohmann::json reply = nlohmann::json::object();
  switch (command.kind) {
    case ControlCommand::Kind::frame: {
      // The frame is submitted, not waited for: "ms" is the last finished frame's.
      const uint64_t before = frames_submitted_;
      wait_for_settled_files();
      iterate(/*render=*/true);
      reply["frame"] = frames_submitted_;
      reply["rendered"] = frames_submitted_ > before;
      reply["view"] = {layout_.view.width, layout_.view.height};  // the frame's size; `inspect` takes its pixels
      reply["time"] = live_->time();  // the instant this frame shows
      reply["ms"] = frame_stats_.wall_ms;
      reply["changed"] = reloaded_files_;
      reply["shaders_reloaded"] = shaders_reloaded_;
      reply["scene_reloaded"] = scene_reloaded_;
      reply["error"] = live_->error() ? nlohmann::json(live_->error()->summary()) : nlohmann::json(nullptr);
      reply["validation_messages"] = ctx_.validation_log().count();
      // The last finished frame's (timing_log_ holds that frame alone).
      reply["pages_pending"] = timing_log_.frames().empty() ? 0u : timing_log_.frames().back().pages_pending;
#ifdef __GLIBC__
      // What the program holds, unlike resident memory, which freed heap pages still count in.
      const struct mallinfo2 heap = mallinfo2();
      reply["heap_in_use_bytes"] = heap.uordblks + heap.hblkhd;
#endif
      reloaded_files_.clear();
      shaders_reloaded_ = scene_reloaded_ = false;
      break;
    }
    case ControlCommand::Kind::inspect:
      inspect_pixel(command.pixel);
      reply["inspect"] = inspector_.active() ? nlohmann::json(inspector_.description()) : nlohmann::json(nullptr);
      break;
    case ControlCommand::Kind::screenshot:
      if (frames_submitted_ == 0) throw std::invalid_argument("screenshot: no frame rendered yet");
      screenshot_dir_ = command.directory;
      iterate(/*render=*/false);
      reply["screenshot"] = command.directory.string();
      reply["status"] = status_;
      break;
    case ControlCommand::Kind::light:
      if (command.light >= live_->scene().lights.size())
        throw std::invalid_argument("light " + std::to_string(command.light) + ": the scene has " +
                                    std::to_string(live_->scene().lights.size()) + " lights");
      set_light_field(settings_.overrides, command.light, command.field, command.value);
      apply({.scene_edited = true});
      break;
    case ControlCommand::Kind::exposure:
      settings_.exposure = command.exposure;
      apply({.exposure_changed = true});
      break;
    case ControlCommand::Kind::orbit:
      camera_.turn_about_target(glm::radians(command.degrees));
      scene_dirty_ = true;
      reply["camera"] = {camera_.camera().position.x, camera_.camera().position.y, camera_.camera().position.z};
      break;
    case ControlCommand::Kind::levels:
      if (command.overlay_light && *command.overlay_light >= live_->scene().lights.size())
        throw std::invalid_argument("levels " + std::to_string(*command.overlay_light) + ": the scene has " +
                                    std::to_string(live_->scene().lights.size()) + " lights");
      settings_.level_overlay = command.overlay_light;
      apply({.level_overlay_changed = true});
      break;
    case ControlCommand::Kind::time:
      timeline_.set_duration(live_->scene().duration());
      if (command.play) {
        *command.play ? timeline_.play() : timeline_.pause();
      } else {
        timeline_.scrub(command.seconds);
        show_time();
      }
      reply["time"] = timeline_.time();
      reply["playing"] = timeline_.playing();
      reply["duration"] = timeline_.duration();
      break;
    case ControlCommand::Kind::quit: break;
  }
  return reply;
}

int ViewerApp::finish() {
  finish_scene_frames();
  vkDeviceWaitIdle(ctx_.device());
  if (options_.inspect_pixel) {
    const fs::path dir = options_.screenshot_dir.empty() ? options_.out_dir : options_.screenshot_dir;
    if (!inspector_.has_values()) {
      std::fprintf(stderr, "avsm-viewer: --inspect: no curve was evaluated (%s)\n",
                   inspector_.active() ? "the point is outside every light's map" : "nothing under that pixel");
      failed_ = true;
    } else {
      fs::create_directories(dir);
      inspector_.write_json(dir / "inspect.json");
      std::fprintf(stderr, "avsm-viewer: %s -> %s\n", inspector_.description().c_str(),
                   (dir / "inspect.json").c_str());
    }
  }
  const std::vector<gpu::ValidationMessage> messages = ctx_.validation_log().take();
  if (!messages.empty()) {
    std::fprintf(stderr, "avsm-viewer: validation reported problems:\n%s\n", gpu::describe(messages).c_str());
    failed_ = true;
  }
  return failed_ ? 1 : 0;
}

void ViewerApp::follow_window_size() {
  const VkExtent2D size = window_.framebuffer_size();
  const VkExtent2D current = swapchain_.extent();
  if (size.width != current.width || size.height != current.height) swapchain_.recreate(size);
  // The window's size or its scale (moved to another screen) may have changed: the panel
  // follows both, the view (and so the renderer) only the size.
  const ViewLayout layout = layout_for({swapchain_.extent().width, swapchain_.extent().height}, window_.framebuffer_scale());
  const bool view_resized = layout.view.width != layout_.view.width || layout.view.height != layout_.view.height;
  layout_ = layout;
  if (!view_resized || layout_.view.empty()) return;  // minimised: the renderer keeps its size
  if (live_->renderer().width() == layout_.view.width && live_->renderer().height() == layout_.view.height) return;
  live_->set_size(layout_.view.width, layout_.view.height);
  ldr_valid_ = false;
  scene_dirty_ = true;
}

void ViewerApp::poll_live() {
  const live::PollResult result = live_->poll();
  edits_pending_ = false;
  files_settling_ = result.waiting;
  if (result.failed && live_->error())
    std::fprintf(stderr, "avsm-viewer: reload failed, keeping the last good version: %s\n",
                 live_->error()->summary().c_str());
  for (const fs::path& file : result.changed) reloaded_files_.push_back(file.string());
  shaders_reloaded_ = shaders_reloaded_ || result.shaders_reloaded;
  scene_reloaded_ = scene_reloaded_ || result.scene_reloaded;
  if (!result.anything_new()) return;
  // New pipelines come with a new renderer, whose output images hold no frame yet.
  if (result.shaders_reloaded) ldr_valid_ = false;
  for (const fs::path& file : result.changed) std::fprintf(stderr, "avsm-viewer: reloaded after %s changed\n", file.c_str());
  if (live_->options().scene_file != scene_file_) {  // another scene: start from its camera
    scene_file_ = live_->options().scene_file;
    camera_.reset(live_->scene().cameras.front());
  }
  refresh_inspection();
  scene_dirty_ = true;
}

void ViewerApp::wait_for_settled_files() {
  const live::SettleTimes& settle = live_->options().settle;
  // A file that never stops changing (or stays missing) is given up on after this.
  const Clock::time_point give_up = Clock::now() + settle.settle + settle.missing + std::chrono::seconds(1);
  poll_live();
  while (files_settling_ && Clock::now() < give_up) {
    std::this_thread::sleep_for(std::chrono::milliseconds(10));
    poll_live();
  }
}

void ViewerApp::handle_input() {
  const ImGuiIO& io = ImGui::GetIO();
  const Clock::time_point now = Clock::now();
  CameraInput input;
  input.seconds = std::chrono::duration<float>(now - last_iteration_).count();
  last_iteration_ = now;
  input.viewport_height = float(layout_.view.height);
  // The mouse works the camera only over the view: the panel (and ImGui's popups over
  // the view) keep it, and a drag counts where its press was, wherever it goes after.
  if (!io.WantCaptureMouse) {
    auto position = [](const ImVec2& p) { return glm::vec2(p.x, p.y); };
    auto held_from_view = [&](ImGuiMouseButton button) {
      return ImGui::IsMouseDown(button) && layout_.in_view(position(io.MouseClickedPos[button]));
    };
    input.mouse_delta = position(io.MouseDelta) * layout_.scale;
    input.rotate = held_from_view(ImGuiMouseButton_Left);
    input.pan_or_look = held_from_view(ImGuiMouseButton_Right) || held_from_view(ImGuiMouseButton_Middle);
    if (layout_.in_view(position(io.MousePos))) input.scroll = io.MouseWheel;
    // A click (not a drag) on the view inspects the texel under it.
    const glm::vec2 clicked = position(io.MouseClickedPos[ImGuiMouseButton_Left]);
    if (ImGui::IsMouseReleased(ImGuiMouseButton_Left) && io.MouseDragMaxDistanceSqr[ImGuiMouseButton_Left] < kClickSlopSquared &&
        layout_.in_view(clicked))
      inspect_pixel(layout_.view_pixel(clicked));
  }
  if (!io.WantCaptureKeyboard) {
    // ImGui 1.86 indexes keys by the backend's (GLFW's) key codes.
    auto axis = [](int positive, int negative) {
      return float(ImGui::IsKeyDown(positive)) - float(ImGui::IsKeyDown(negative));
    };
    input.move = {axis(GLFW_KEY_D, GLFW_KEY_A), axis(GLFW_KEY_E, GLFW_KEY_Q), axis(GLFW_KEY_W, GLFW_KEY_S)};
    input.fast = io.KeyShift;
    if (ImGui::IsKeyPressed(GLFW_KEY_F12, false) || ImGui::IsKeyPressed(GLFW_KEY_P, false))
      apply({.screenshot = true});
    if (ImGui::IsKeyPressed(GLFW_KEY_ESCAPE, false)) window_.request_close();
  }
  if (camera_.update(input)) scene_dirty_ = true;
}

void ViewerApp::advance_timeline(bool render) {
  timeline_.set_duration(live_->scene().duration());
  const Clock::time_point now = Clock::now();
  const double elapsed = options_.control ? (render ? 1.0 / timeline_.fps() : 0.0)
                                          : std::chrono::duration<double>(now - last_tick_).count();
  last_tick_ = now;
  if (timeline_.advance(elapsed)) show_time();
}

void ViewerApp::show_time() {
  finish_scene_frames();  // moving meshes are uploaded: the frames in flight read them
  live_->set_time(timeline_.time(), /*wait_for_sequences=*/options_.control);  // scripted: the time's own frames
  scene_dirty_ = true;
}

void ViewerApp::apply(const PanelRequests& requests) {
  if (requests.time_changed) show_time();
  if (requests.scene_edited) {
    live_->set_scene_edit([overrides = settings_.overrides](scene::Scene& scene) { overrides.apply(scene); });
    edits_pending_ = true;
  }
  if (requests.shadow_options_changed) {
    live_->set_shadow_options(settings_.shadow_options);
    edits_pending_ = true;
  }
  if (requests.exposure_changed) {
    live_->renderer().set_exposure(settings_.exposure);
    scene_dirty_ = true;
  }
  if (requests.level_overlay_changed) {
    finish_scene_frames();  // the frames in flight were declared without (or with) the overlay's passes
    live_->renderer().set_level_overlay(settings_.level_overlay);
    scene_dirty_ = true;
  }
  if (requests.load_scene) {
    live_->set_scene_file(*requests.load_scene);
    edits_pending_ = true;
  }
  if (requests.reset_camera) {
    camera_.reset(live_->scene().cameras.front());
    scene_dirty_ = true;
  }
  if (requests.camera_mode) camera_.mode = *requests.camera_mode;
  if (requests.inspect_light_texel) {
    ensure_reference();
    inspector_.inspect_light_texel(requests.inspect_light_texel->first, requests.inspect_light_texel->second);
    refresh_inspection();
  }
  if (requests.clear_inspection) inspector_.clear();
  if (requests.screenshot) {
    if (frames_submitted_ == 0)
      set_status("no frame to save yet");
    else
      screenshot_dir_ = next_shot_dir(options_.out_dir);
  }
}

void ViewerApp::inspect_pixel(glm::vec2 pixel) {
  const renderer::SceneRenderer& renderer = live_->renderer();
  if (pixel.x < 0 || pixel.y < 0 || pixel.x >= float(renderer.width()) || pixel.y >= float(renderer.height())) {
    set_status("pixel (" + std::to_string(int(pixel.x)) + ", " + std::to_string(int(pixel.y)) + ") is outside the " +
               std::to_string(renderer.width()) + "x" + std::to_string(renderer.height()) + " view");
    return;
  }
  if (!inspector_.inspect_pixel(live_->scene(), current_view(), pixel)) {
    set_status("nothing under pixel (" + std::to_string(int(pixel.x)) + ", " + std::to_string(int(pixel.y)) + ")");
    return;
  }
  ensure_reference();
  refresh_inspection();
}

// The curves compare against the exact transmittance, which only frames that keep
// the capture lists have. Switched on at the first inspection (it costs memory).
void ViewerApp::ensure_reference() {
  if (settings_.shadow_options.keep_reference) return;
  settings_.shadow_options.keep_reference = true;
  live_->set_shadow_options(settings_.shadow_options);
  edits_pending_ = true;
}

void ViewerApp::refresh_inspection() {
  if (!inspector_.active()) return;
  finish_scene_frames();  // their curves are of the samples set so far
  renderer::SceneRenderer& renderer = live_->renderer();
  // The texels of the maps the next frame builds, which follow the camera.
  renderer.fit_shadows_to(current_view());
  const std::vector<passes::TexelSample> samples = inspector_.prepare(live_->scene(), renderer.shadows().light_views());
  try {
    // The first inspection builds the curve pass from source: a shader broken on disk
    // right now (its edit waiting for a fix) must not take the viewer down.
    if (!samples.empty()) renderer.set_texel_samples(samples);
  } catch (const std::exception& e) {
    set_status(std::string("texel inspection failed: ") + e.what());
    return;
  }
  scene_dirty_ = true;
}

passes::View ViewerApp::current_view() {
  const renderer::SceneRenderer& renderer = live_->renderer();
  return passes::make_view(camera_.camera(), renderer.width(), renderer.height());
}

void ViewerApp::set_status(const std::string& text) {
  status_ = text;
  std::fprintf(stderr, "avsm-viewer: %s\n", text.c_str());
}

void ViewerApp::render_scene_frame() {
  renderer::SceneRenderer& renderer = live_->renderer();
  // Cleared first: a frame that finishes as its slot is taken may ask for another.
  scene_dirty_ = false;
  renderer::FrameSlots::Slot& slot =
      scene_slots_.acquire([this](renderer::FrameSlots::Slot& done) { scene_frame_finished(done); });
  bool new_textures = false;
  scene_clocks_[slot.index] = capture::record_timed_frame(
      renderer, *slot.executor, slot.cmd, current_view(), slot.index, [&](VkCommandBuffer cmd) {
        // New textures replace those the window frames in flight sample: let them finish.
        if (light_maps_.would_recreate(renderer.light_images())) window_slots_.finish_all({});
        new_textures = light_maps_.record_copies(cmd, renderer.light_images());
      });
  scene_slots_.submit(slot);
  ++frames_submitted_;
  ldr_valid_ = true;

  // The window frames after this one sample the textures, which this frame writes first.
  if (new_textures) {
    const std::vector<gpu::Image>& textures = light_maps_.textures();
    light_map_ids_.resize(std::min(light_map_ids_.size(), textures.size()));
    for (size_t i = 0; i < textures.size(); ++i) {
      if (i < light_map_ids_.size())
        imgui_renderer_.replace_texture(light_map_ids_[i], textures[i].view());
      else
        light_map_ids_.push_back(imgui_renderer_.add_texture(textures[i].view()));
    }
  }
}

void ViewerApp::scene_frame_finished(renderer::FrameSlots::Slot& slot) {
  renderer::SceneRenderer& renderer = live_->renderer();
  capture::FrameClock& clock = scene_clocks_[slot.index];
  clock.completed = Clock::now();
  renderer.finish_frame(slot.index);
  // The screenshot's timings.json describes this frame alone.
  timing_log_.clear();
  const std::vector<rg::vulkan::PassTiming> timings = slot.executor->read_timings();
  const double wall = timing_log_.add_frame(clock, timings, renderer.shadows().frame_stats(), /*measured=*/true);
  frame_stats_ = {frame_stats_.number + 1, wall, timings};

  // A capture that overflowed dropped segments; its buffers grew, so render again.
  bool overflowed = false;
  for (const passes::LightShadowStats& light : renderer.shadows().frame_stats()) {
    overflowed = overflowed || light.lost_shadowing();
    scene_dirty_ = scene_dirty_ || light.grew;
  }
  overflowed_frames_ += overflowed;
  if (inspector_.active())
    inspector_.read_results(renderer.texel_results(), ctx_, renderer.shadows(), live_->scene());
  window_.set_title("avsm-viewer - " + scene_file_.filename().string() + " - " +
                    std::to_string(int(wall)) + " ms per frame");
}

void ViewerApp::finish_scene_frames() {
  scene_slots_.finish_all([this](renderer::FrameSlots::Slot& slot) { scene_frame_finished(slot); });
}

void ViewerApp::present(const ImDrawData& draw_data) {
  // Waits for the slot's previous window frame: its acquire semaphore, panel buffers and
  // executor are free again.
  renderer::FrameSlots::Slot& slot = window_slots_.acquire({});
  const std::optional<uint32_t> image = swapchain_.acquire(slot.index);
  if (!image) {
    swapchain_.recreate(window_.framebuffer_size());
    return;
  }
  const bool read_back = screenshot_dir_ && swapchain_.can_read_back();
  const VkExtent2D extent = swapchain_.extent();
  if (read_back) {
    const VkDeviceSize bytes = VkDeviceSize(extent.width) * extent.height * 4;
    if (!window_readback_ || window_readback_.size() < bytes)
      window_readback_ = gpu::Buffer::create(
          ctx_, {bytes, VK_BUFFER_USAGE_TRANSFER_DST_BIT, gpu::MemoryLocation::HostReadback, "window readback"});
  }
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  VK_CHECK(vkBeginCommandBuffer(slot.cmd, &begin));
  record_window(slot, *image, draw_data, read_back);
  VK_CHECK(vkEndCommandBuffer(slot.cmd));
  window_slots_.submit(slot, swapchain_.acquired(slot.index), Swapchain::kAcquireWaitStages,
                       swapchain_.rendered(*image));
  const bool presented = swapchain_.present(*image);

  if (screenshot_dir_) {
    // The files describe completed frames: the scene's and this window frame.
    finish_scene_frames();
    window_slots_.finish_all({});
    const fs::path dir = *screenshot_dir_;
    screenshot_dir_.reset();
    std::vector<uint8_t> window_rgba;
    if (read_back) window_rgba = swapchain_.to_rgba(static_cast<const uint8_t*>(window_readback_.mapped()));
    write_screenshot(dir, window_rgba);
  }
  if (!presented) swapchain_.recreate(window_.framebuffer_size());
}

// The frame into the swapchain image, as a small frame graph of its own: a grey clear,
// the scene blitted into the view's rectangle (once a frame of the view's size exists),
// then the panel in its column, then (for a screenshot) a copy into the readback buffer. The graph plans every layout transition, from the acquired image
// (contents undefined; the submit waits for it at Swapchain::kAcquireWaitStages) to
// PRESENT_SRC_KHR, and the readback buffer's host-read state.
void ViewerApp::record_window(renderer::FrameSlots::Slot& slot, uint32_t image, const ImDrawData& draw_data,
                              bool read_back) {
  rg::Graph graph;
  const gpu::Image& swapchain_image = swapchain_.target(image);
  const rg::ImportState acquired{Swapchain::kAcquireWaitStages, VK_ACCESS_2_NONE, VK_IMAGE_LAYOUT_UNDEFINED};
  rg::TextureHandle target =
      rg::vulkan::import(graph, "swapchain image", swapchain_image, acquired, rg::ImportState::of(rg::Usage::Present));
  target = add_grey_clear(graph, target);
  if (ldr_valid_) target = add_scene_blit(graph, target);
  target = add_panel(graph, target, draw_data, slot.index);
  if (read_back) add_window_readback(graph, target, image);
  slot.executor->record(graph, slot.cmd);
}

// The tonemapped image holds display values: copied, not converted, into the view's
// rectangle, pixel for pixel (the renderer renders at the view's size; were it ever
// larger, the excess is cut off, never scaled).
rg::TextureHandle ViewerApp::add_scene_blit(rg::Graph& graph, rg::TextureHandle target) {
  const gpu::Image& ldr = live_->renderer().ldr();
  // The state the scene graph leaves it in (its final state), which it keeps.
  static_assert(renderer::SceneRenderer::kOutputLayout == VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  const rg::ImportState scene_output = rg::ImportState::of(rg::Usage::TransferSrc);
  const rg::TextureHandle source = rg::vulkan::import(graph, "tonemapped", ldr, scene_output, scene_output);
  graph.add_pass("blit scene", rg::QueueType::Transfer,
      [&](rg::PassBuilder& b) {
        b.read(source, rg::Usage::TransferSrc);
        target = b.write(target, rg::Usage::TransferDst);
      },
      [source, target, view = layout_.view](rg::PassContext& c) {
        const rg::TextureDesc &from = c.desc(source), &to = c.desc(target);
        const int32_t width = int32_t(std::min({from.width, view.width, to.width - std::min(view.x, to.width)}));
        const int32_t height = int32_t(std::min({from.height, view.height, to.height - std::min(view.y, to.height)}));
        if (width <= 0 || height <= 0) return;
        VkImageBlit region{};
        region.srcSubresource = region.dstSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        region.srcOffsets[1] = {width, height, 1};
        region.dstOffsets[0] = {int32_t(view.x), int32_t(view.y), 0};
        region.dstOffsets[1] = {int32_t(view.x) + width, int32_t(view.y) + height, 1};
        vkCmdBlitImage(c.cmd(), c.image(source), c.layout(source), c.image(target), c.layout(target), 1, &region,
                       VK_FILTER_NEAREST);
      });
  return target;
}

// The whole window: the panel's column under the panel, and the view until the first
// scene frame of its size.
rg::TextureHandle ViewerApp::add_grey_clear(rg::Graph& graph, rg::TextureHandle target) {
  graph.add_pass("clear window", rg::QueueType::Transfer,
      [&](rg::PassBuilder& b) { target = b.write(target, rg::Usage::TransferDst); },
      [target](rg::PassContext& c) {
        const VkClearColorValue grey{{0.1f, 0.1f, 0.12f, 1.0f}};
        const VkImageSubresourceRange range = colour_range();
        vkCmdClearColorImage(c.cmd(), c.image(target), c.layout(target), &grey, 1, &range);
      });
  return target;
}

// The panel draws into its column (load op LOAD; the scene is beside it). The textures it samples (font, light
// maps) are not graph resources: they stay in SHADER_READ_ONLY_OPTIMAL, and whoever
// last wrote them left them visible to fragment shaders.
rg::TextureHandle ViewerApp::add_panel(rg::Graph& graph, rg::TextureHandle target, const ImDrawData& draw_data,
                                       uint32_t slot) {
  graph.add_pass("panel", rg::QueueType::Graphics,
      [&](rg::PassBuilder& b) { target = b.read_write(target, rg::Usage::ColorAttachment); },
      [this, target, &draw_data, slot](rg::PassContext& c) {
        const rg::TextureDesc& size = c.desc(target);
        imgui_renderer_.record(c.cmd(), draw_data, c.view(target), {size.width, size.height}, slot);
      });
  return target;
}

void ViewerApp::add_window_readback(rg::Graph& graph, rg::TextureHandle target, uint32_t image) {
  const rg::BufferHandle readback = rg::vulkan::import(graph, "window readback", window_readback_, rg::ImportState::none(),
                                                       rg::ImportState::of(rg::Usage::HostRead));
  graph.add_pass("read back window", rg::QueueType::Transfer,
      [&](rg::PassBuilder& b) {
        b.read(target, rg::Usage::TransferSrc);
        b.write(readback, rg::Usage::TransferDst);
      },
      [this, image](rg::PassContext& c) { swapchain_.record_readback(c.cmd(), image, window_readback_); });
}

void ViewerApp::write_screenshot(const fs::path& dir, const std::vector<uint8_t>& window_rgba) {
  try {
    const renderer::SceneRenderer& renderer = live_->renderer();
    capture::write_frame_outputs(dir, {ctx_, renderer, scene_slots_.last_finished_executor(), live_->scene(), timing_log_, overflowed_frames_});
    if (!window_rgba.empty()) write_rgba_png(dir / "window.png", window_rgba, swapchain_.extent());
    write_layout(dir / "layout.json");
    if (inspector_.has_values()) inspector_.write_json(dir / "inspect.json");
    set_status("saved " + dir.string());
  } catch (const std::exception& e) {
    set_status(std::string("screenshot failed: ") + e.what());
    if (options_.frames > 0) failed_ = true;  // a scripted run must not pass without its files
  }
}

// layout.json: where the panel and the view (frame.png) lie in window.png.
void ViewerApp::write_layout(const fs::path& path) const {
  auto rect = [](const PixelRect& r) {
    return nlohmann::json{{"x", r.x}, {"y", r.y}, {"width", r.width}, {"height", r.height}};
  };
  const nlohmann::json json{{"window", {layout_.framebuffer.x, layout_.framebuffer.y}},
                            {"scale", {layout_.scale.x, layout_.scale.y}},
                            {"panel", rect(layout_.panel)},
                            {"view", rect(layout_.view)}};
  std::ofstream(path) << json.dump(1) << "\n";
}

}  // namespace

int run_viewer(const ViewerOptions& options) {
  ViewerApp app(options);
  return app.run();
}

}  // namespace avsm::viewer
