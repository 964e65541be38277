#include "live/live_renderer.h"

#include <cstdio>

#include <fstream>
#include <map>
#include <set>
#include <sstream>
#include <stdexcept>
#include <utility>

#include <nlohmann/json.hpp>

#include "io/file_time.h"
#include "scene/description.h"
#include "scene/load_error.h"

namespace avsm::live {
namespace fs = std::filesystem;

namespace {

// The external buffers and images of a .gltf (not data URIs): re-exporting a
// model often rewrites only its .bin. Unreadable JSON adds nothing; loading
// the model reports it.
std::vector<fs::path> gltf_resources(const fs::path& gltf) {
  std::vector<fs::path> files;
  if (gltf.extension() != ".gltf") return files;
  std::ifstream in(gltf);
  const nlohmann::json json = nlohmann::json::parse(in, nullptr, /*allow_exceptions=*/false);
  if (!json.is_object()) return files;
  for (const char* list : {"buffers", "images"}) {
    auto entries = json.find(list);
    if (entries == json.end() || !entries->is_array()) continue;
    for (const nlohmann::json& entry : *entries) {
      auto uri = entry.find("uri");
      if (uri == entry.end() || !uri->is_string()) continue;
      const std::string text = uri->get<std::string>();
      if (text.rfind("data:", 0) != 0) files.push_back(gltf.parent_path() / text);
    }
  }
  return files;
}

// The files a scene is made of: the scene file and every asset it references.
// The files a scene was loaded from. A volume sequence is watched by its first and last
// frames (a simulation written again rewrites both), not frame by frame.
std::vector<fs::path> scene_files(const scene::SceneDescription& description, const scene::Scene& scene) {
  std::vector<fs::path> files{description.file};
  for (const scene::ModelEntry& model : description.models) {
    files.push_back(model.file);
    for (const fs::path& resource : gltf_resources(model.file)) files.push_back(resource);
  }
  for (const scene::VolumeEntry& volume : description.volumes)
    if (!scene::parse_frame_pattern(volume.file)) files.push_back(volume.file);
  for (const scene::VolumeSequence& sequence : scene.volume_sequences) {
    files.push_back(sequence.pattern.file(sequence.timing.first));
    files.push_back(sequence.pattern.file(sequence.timing.last));
  }
  for (const scene::HairEntry& hair : description.hair) files.push_back(hair.file);
  return files;
}

// The line of a message worth showing next to file:line: glslang's first
// "ERROR: file:line: what" without its location, else the first line without a
// leading "file: " (loaders name the file first).
std::string headline(const std::string& message, const fs::path& file) {
  std::istringstream lines(message);
  for (std::string line; std::getline(lines, line);) {
    const size_t error = line.find("ERROR: ");
    if (error == std::string::npos) continue;
    const size_t what = line.find(": ", line.find(':', line.find(':', error + 7) + 1));
    return what == std::string::npos ? line.substr(error + 7) : line.substr(what + 2);
  }
  std::string first = message.substr(0, message.find('\n'));
  for (const std::string& prefix : {file.string() + ": ", file.filename().string() + ": "})
    if (!prefix.empty() && first.rfind(prefix, 0) == 0) return first.substr(prefix.size());
  return first;
}

}  // namespace

std::string ReloadError::summary() const {
  std::ostringstream out;
  out << (file.empty() ? std::string("edit") : file.string());
  if (line > 0) out << ':' << line;
  out << ": " << headline(message, file);
  return out.str();
}

LiveRenderer::LiveRenderer(gpu::Context& ctx, LiveOptions options)
    : ctx_(ctx),
      options_(std::move(options)),
      shaders_(std::make_unique<gpu::ShaderLibrary>(options_.shader_paths, /*compile_from_source=*/true)),
      scene_files_(options_.settle),
      shader_files_(options_.settle),
      next_shadow_options_(options_.shadow_options) {
  const scene::SceneDescription description = scene::read_scene_description(options_.scene_file);
  loaded_ = scene::load_scene(description);
  edited_ = loaded_;
  edited_.animation.pose(edited_, time_);
  renderer_ = make_renderer(edited_);
  restart_sequences();
  scene_files_.watch(scene_files(description, loaded_));
  shader_files_.watch(shaders_->source_files());
}

void LiveRenderer::restart_sequences() {
  shown_frames_.clear();
  sequence_error_.reset();
  sequences_.reset();  // its worker stops before the new one starts
  if (edited_.volume_sequences.empty()) return;
  // Frames are read with the scene file's settings, and the editor's changes to a volume's
  // optics (scene_overrides) follow into every frame read from now on.
  std::vector<scene::VolumeSequence> sequences = edited_.volume_sequences;
  for (scene::VolumeSequence& sequence : sequences) {
    const scene::Volume& edited = edited_.volumes[sequence.volume];
    sequence.entry.extinction_scale = edited.extinction_scale;
    sequence.entry.albedo = edited.albedo;
    sequence.entry.multiple_scattering = edited.multiple_scattering;
    sequence.entry.sky_light = edited.sky_light;
  }
  sequences_ = std::make_unique<renderer::VolumeSequencePlayer>(std::move(sequences), ctx_.info().max_image_dimension_3d);
  // The renderer holds the frame of time 0 (the scene's): the time's own, before the next frame.
  try {
    show_sequence_frames(/*wait=*/true);
  } catch (const scene::LoadError& e) {
    sequence_error_ = ReloadError{e.file(), 0, e.what()};
  }
}

bool LiveRenderer::show_sequence_frames(bool wait) {
  if (!sequences_) return false;
  const std::vector<renderer::VolumeSequencePlayer::Shown> shown = sequences_->at(time_, wait);
  for (const renderer::VolumeSequencePlayer::Shown& frame : shown) {
    renderer_->show_volume_frame(frame.volume, frame.part);
    shown_frames_[frame.volume] = frame;
  }
  const std::vector<scene::LoadError> errors = sequences_->take_errors();
  if (!errors.empty()) {
    sequence_error_ = ReloadError{errors.back().file(), 0, errors.back().what()};
    std::fprintf(stderr, "avsm-viewer: %s (the volume keeps its last frame)\n", errors.back().what());
  } else if (!shown.empty()) {
    sequence_error_.reset();
  }
  return !shown.empty();
}

void LiveRenderer::set_time(float time, bool wait_for_sequences) {
  time_ = time;
  try {
    show_sequence_frames(wait_for_sequences);
  } catch (const scene::LoadError& e) {  // waited for a frame that cannot be read: it keeps the last
    sequence_error_ = ReloadError{e.file(), 0, e.what()};
    update_error();
  }
  if (edited_.animation.empty()) return;
  edited_.animation.pose(edited_, time);
  for (std::size_t light : edited_.animation.moving_lights())
    renderer_->place_light(uint32_t(light), edited_.lights[light].position, edited_.lights[light].direction);
  for (std::size_t mesh : edited_.animation.moving_meshes()) renderer_->update_mesh(uint32_t(mesh), edited_.meshes[mesh]);
}

void LiveRenderer::update_error() { error_ = shader_error_ ? shader_error_ : scene_error_ ? scene_error_ : sequence_error_; }

LiveRenderer::~LiveRenderer() {
  if (renderer_) vkDeviceWaitIdle(ctx_.device());
}

std::unique_ptr<renderer::SceneRenderer> LiveRenderer::make_renderer(const scene::Scene& scene) const {
  auto fresh = std::make_unique<renderer::SceneRenderer>(ctx_, *shaders_, scene, options_.width, options_.height,
                                                         options_.shadow_options);
  if (setup_) setup_(*fresh);
  return fresh;
}

void LiveRenderer::set_scene_edit(std::function<void(scene::Scene&)> edit) {
  edit_ = std::move(edit);
  edits_dirty_ = true;
}

void LiveRenderer::set_shadow_options(const passes::ShadowOptions& options) {
  next_shadow_options_ = options;
  edits_dirty_ = true;
}

void LiveRenderer::set_size(uint32_t width, uint32_t height) {
  options_.width = width;
  options_.height = height;
  if (before_change_) before_change_();
  renderer_->set_size(width, height);
}

void LiveRenderer::set_scene_file(const fs::path& file) {
  next_scene_file_ = file;
  files_dirty_ = true;
}

void LiveRenderer::set_renderer_setup(std::function<void(renderer::SceneRenderer&)> setup) {
  setup_ = std::move(setup);
  if (setup_) setup_(*renderer_);
}

std::vector<fs::path> LiveRenderer::watched_files() const {
  std::set<fs::path> files;
  for (const fs::path& file : scene_files_.files()) files.insert(file);
  for (const fs::path& file : shader_files_.files()) files.insert(file);
  return {files.begin(), files.end()};
}

PollResult LiveRenderer::poll(Clock::time_point now) {
  PollResult result;
  const std::vector<fs::path> scene_changes = scene_files_.settled_changes(now);
  const std::vector<fs::path> shader_changes = shader_files_.settled_changes(now);
  result.changed = scene_changes;
  result.changed.insert(result.changed.end(), shader_changes.begin(), shader_changes.end());
  if (!scene_changes.empty()) files_dirty_ = true;

  // The scene first, so new pipelines are built for the scene they will draw.
  if (files_dirty_ || edits_dirty_) reload_scene(files_dirty_, now, result);
  if (!shader_changes.empty()) reload_shaders(now, result);
  result.sequence_frames = show_sequence_frames(/*wait=*/false);  // frames read since the last poll
  update_error();
  result.waiting = scene_files_.busy() || shader_files_.busy();
  return result;
}

void LiveRenderer::reload_shaders(Clock::time_point now, PollResult& result) {
  std::unique_ptr<renderer::SceneRenderer> fresh;
  std::optional<ReloadError> failure;
  if (options_.before_reading) options_.before_reading();
  try {
    fresh = make_renderer(edited_);
  } catch (const gpu::ShaderCompileError& e) {
    failure = ReloadError{e.file(), e.line(), e.what()};
  } catch (const std::exception& e) {
    // Pipeline creation or a missing file: name the last changed shader.
    failure = ReloadError{result.changed.empty() ? fs::path() : result.changed.back(), 0, e.what()};
  }
  // A source written to while it compiled: neither its pipelines nor its errors count.
  if (!shader_files_.confirm(now)) return;
  if (failure) {
    shader_error_ = std::move(failure);
    result.failed = true;
    return;
  }
  shader_error_.reset();
  if (before_change_) before_change_();
  vkDeviceWaitIdle(ctx_.device());  // the old pipelines may still be in flight
  renderer_ = std::move(fresh);
  for (const auto& [volume, shown] : shown_frames_) renderer_->show_volume_frame(volume, shown.part);
  // A new include may have appeared; watch what the good shaders are made of now.
  shader_files_.watch(shaders_->source_files());
  result.shaders_reloaded = true;
}

void LiveRenderer::reload_scene(bool read_files, Clock::time_point now, PollResult& result) {
  const fs::path file = next_scene_file_.value_or(options_.scene_file);
  const bool edits_were_dirty = edits_dirty_;
  files_dirty_ = false;
  edits_dirty_ = false;
  next_scene_file_.reset();

  scene::SceneDescription description;
  scene::Scene fresh_loaded;
  std::optional<ReloadError> failure;
  if (read_files && options_.before_reading) options_.before_reading();
  try {
    if (read_files) {
      description = scene::read_scene_description(file);
      fresh_loaded = scene::load_scene(description);
    } else {
      fresh_loaded = loaded_;
    }
  } catch (const scene::LoadError& e) {
    failure = ReloadError{e.file(), 0, e.what()};
  } catch (const std::exception& e) {
    failure = ReloadError{file, 0, e.what()};
  }
  // A file written to while it was read: what was read (good or not) is not final.
  // The watcher hands the files out again once they settle; the request waits for them.
  if (read_files && !scene_files_.confirm(now)) {
    if (file != options_.scene_file) next_scene_file_ = file;
    edits_dirty_ = edits_were_dirty;
    return;
  }
  if (failure) {
    scene_error_ = std::move(failure);
    result.failed = true;
    return;
  }

  scene::Scene fresh_edited = fresh_loaded;
  try {
    if (edit_) edit_(fresh_edited);
    fresh_edited.animation.pose(fresh_edited, time_);
    if (before_change_) before_change_();
    renderer_->set_scene(fresh_edited, next_shadow_options_);
  } catch (const std::exception& e) {
    // The renderer may be half-updated: give it the last good scene back.
    renderer_->set_scene(edited_, options_.shadow_options);
    // Settings from the files, or the editor's own (no file to blame).
    scene_error_ = ReloadError{read_files ? file : fs::path(), 0, e.what()};
    result.failed = true;
    return;
  }
  scene_error_.reset();
  loaded_ = std::move(fresh_loaded);
  edited_ = std::move(fresh_edited);
  restart_sequences();
  options_.shadow_options = next_shadow_options_;
  if (read_files) {
    options_.scene_file = file;
    scene_files_.watch(scene_files(description, loaded_));
  }
  result.scene_reloaded = true;
}

}  // namespace avsm::live
