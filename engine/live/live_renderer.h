#pragma once
// The authoring loop's renderer: a SceneRenderer that follows its files. It
// watches the scene file, every asset the scene references and every shader
// source (with its #includes), and on the first poll() after an edit has settled
// (live/file_watcher.h: the file held still for LiveOptions::settle) it reloads
// what changed:
//   - a shader: recompiles it (glslang, from source) and rebuilds the pipelines;
//   - the scene file or an asset: loads the scene again and hands it to the renderer;
//   - the editor's overrides (set_scene_edit): re-applies them to the loaded scene.
// A reload that fails (a compile error, a malformed file) changes nothing: the
// last good scene and pipelines keep rendering and error() says what failed,
// naming the file and, for shaders, the line. The next successful reload clears it.
// Files are read the way editors save them: a file being written (in chunks, or
// several times in a row) is read once it held still; a file that vanished (deleted
// then recreated, renamed over) is waited for, not reported, for a while; and a read
// that overlapped a write is dropped (not loaded, not reported) and retried.
// Nothing here needs a window: the viewer drives it, and so do the tests.
#include <filesystem>
#include <functional>
#include <map>
#include <memory>
#include <optional>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "gpu/shader_compiler.h"
#include "live/file_watcher.h"
#include "passes/shadows/shadow_maps.h"
#include "renderer/scene_renderer.h"
#include "renderer/volume_sequence_player.h"
#include "scene/scene.h"

namespace avsm::live {

// What a failed reload reports; the previous content stays in use.
struct ReloadError {
  std::filesystem::path file;  // the file at fault (a shader, the scene file, an asset); empty for an edit
  int line = 0;                // 0 when unknown (asset and scene errors)
  std::string message;         // the loader's or compiler's full message
  std::string summary() const; // "file:line: what went wrong" (one line; "edit: ..." without a file)
};

struct LiveOptions {
  std::filesystem::path scene_file;
  uint32_t width = 640, height = 360;
  passes::ShadowOptions shadow_options;
  // Shader sources to compile and watch (source_root/shaders/...); spirv_root is unused.
  gpu::ShaderLibrary::Paths shader_paths = gpu::ShaderLibrary::default_paths();
  // How long an edited file must hold still before it is read, and how long a
  // vanished one is waited for.
  SettleTimes settle;
  // Called when a reload is about to read settled files (scene, assets or shaders):
  // tests land an editor's next write there, as if it came during the read.
  std::function<void()> before_reading;
};

// What one poll() did.
struct PollResult {
  std::vector<std::filesystem::path> changed;  // watched files whose change settled and was read
  bool shaders_reloaded = false;               // new pipelines are in use
  bool scene_reloaded = false;                 // the scene (file, assets or edits) was handed to the renderer again
  bool failed = false;                         // a reload failed; error() has it
  bool waiting = false;                        // a change is still settling (or was read mid-write): poll again
  bool sequence_frames = false;                // volume sequence frames read since were handed to the renderer
  bool anything_new() const { return shaders_reloaded || scene_reloaded || sequence_frames; }
};

class LiveRenderer {
 public:
  // Loads the scene and compiles every shader from source. Throws (std::runtime_error,
  // scene::LoadError, gpu::ShaderCompileError) when this first load fails: there is
  // nothing yet to fall back to.
  LiveRenderer(gpu::Context& ctx, LiveOptions options);
  ~LiveRenderer();

  // Overrides applied to the loaded scene before rendering (light settings,
  // extinction scale, hair width...), now and after every reload of the scene.
  // Takes effect on the next poll().
  void set_scene_edit(std::function<void(scene::Scene&)> edit);
  // Takes effect on the next poll() (a failure there keeps the old ones).
  void set_shadow_options(const passes::ShadowOptions& options);
  void set_size(uint32_t width, uint32_t height);
  // Puts the scene's animation at `time` (seconds; scene/animation.h): the lights and meshes
  // that move are handed to the renderer now. Reloads and edits keep the time.
  // Volume sequences' frames go to the renderer as the player has them read; with
  // `wait_for_sequences`, this waits for them (scripted runs, which must show the time's own).
  void set_time(float time, bool wait_for_sequences = false);
  float time() const { return time_; }
  // The file frame a volume sequence shows (handed to the renderer for its next frame),
  // or nullopt for a volume that is no sequence or has none yet.
  std::optional<int> sequence_frame(uint32_t volume) const {
    const auto it = shown_frames_.find(volume);
    return it == shown_frames_.end() ? std::nullopt : std::optional(it->second.frame);
  }
  // Loads another scene file on the next poll() (same rules: a bad file keeps the current scene).
  void set_scene_file(const std::filesystem::path& file);
  // Called on the renderer now and on every new one (a shader reload builds a new
  // SceneRenderer): enable probes, light images, texel samples, exposure here.
  void set_renderer_setup(std::function<void(renderer::SceneRenderer&)> setup);
  // Called just before the renderer is changed or replaced (a reload that succeeded, a
  // new size): a host with frames in flight finishes them there, as their results
  // belong to the renderer as it was.
  void set_before_change(std::function<void()> before_change) { before_change_ = std::move(before_change); }

  // Checks the watched files' sizes and time stamps and reloads what changed (once
  // settled) or was asked for. Cheap when nothing changed. Waits for the device to
  // idle before it replaces anything, so call it between frames.
  PollResult poll() { return poll(Clock::now()); }
  // The same at a given time (tests drive the settle time with it).
  PollResult poll(Clock::time_point now);

  // The last failed reload; empty once a reload succeeds.
  const std::optional<ReloadError>& error() const { return error_; }

  renderer::SceneRenderer& renderer() { return *renderer_; }
  const scene::Scene& scene() const { return edited_; }        // what is being rendered
  const scene::Scene& loaded_scene() const { return loaded_; }  // as read from the files
  const LiveOptions& options() const { return options_; }
  const gpu::ShaderLibrary& shaders() const { return *shaders_; }
  // Every file being watched (scene, assets, shader sources and includes).
  std::vector<std::filesystem::path> watched_files() const;

 private:
  void reload_shaders(Clock::time_point now, PollResult& result);
  void reload_scene(bool read_files, Clock::time_point now, PollResult& result);

  std::unique_ptr<renderer::SceneRenderer> make_renderer(const scene::Scene& scene) const;

  gpu::Context& ctx_;
  LiveOptions options_;
  std::unique_ptr<gpu::ShaderLibrary> shaders_;
  std::unique_ptr<renderer::SceneRenderer> renderer_;
  // The volume sequences of the scene as edited, read ahead as the time moves; what the
  // renderer shows of them (given again to a renderer that replaces it).
  std::unique_ptr<renderer::VolumeSequencePlayer> sequences_;
  std::map<uint32_t, renderer::VolumeSequencePlayer::Shown> shown_frames_;  // by volume
  void restart_sequences();
  // Hands the renderer the sequence frames of the current time that are ready (`wait`: waits for them).
  // Returns whether it handed any.
  bool show_sequence_frames(bool wait);
  void update_error();  // error_ from the three below
  scene::Scene loaded_, edited_;
  std::function<void(scene::Scene&)> edit_;
  float time_ = 0.0f;
  std::function<void(renderer::SceneRenderer&)> setup_;
  std::function<void()> before_change_;
  FileWatcher scene_files_, shader_files_;
  std::optional<ReloadError> shader_error_, scene_error_;
  std::optional<ReloadError> sequence_error_;  // a sequence frame that could not be read (the last good one stays)
  std::optional<ReloadError> error_;  // the shader error if any, else the scene error, else the sequence error
  bool files_dirty_ = false;   // read the scene and its assets again
  bool edits_dirty_ = false;   // apply edits / shadow options / size again
  std::optional<std::filesystem::path> next_scene_file_;
  passes::ShadowOptions next_shadow_options_;
};

}  // namespace avsm::live
