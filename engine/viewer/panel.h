#pragma once
// The viewer's Dear ImGui panel: the scene file, per light technique / node count /
// map resolution / filter / sort / on-off, placement (a point light's position and
// range), fit / cascades / clusters and the maps the last frame made of it (kind,
// count, budget lowering), volume extinction and
// albedo, hair opacity and width, exposure, the shadow level overlay; the last frame's per-pass GPU timings,
// memory figures and frame-graph plan; reload errors; the light maps and the
// inspected texel's transmittance curves. It edits ViewerSettings and returns what
// else the user asked for; the viewer app acts on it. It is docked: a column at the
// window's left edge, full height, that the user cannot move, resize or collapse; the
// 3D view takes the rest of the window (viewer/view_layout.h).
#include <imgui.h>
#include <rendergraph/plan.h>
#include <rendergraph/vulkan/executor.h>

#include <optional>
#include <string>
#include <vector>

#include "live/live_renderer.h"
#include "passes/shadows/shadow_maps.h"
#include "viewer/camera_controller.h"
#include "viewer/scene_overrides.h"
#include "viewer/texel_inspector.h"
#include "viewer/timeline.h"
#include "viewer/view_layout.h"

namespace avsm::viewer {

// A light's maps as the panel shows them: "single map, 1024^2", "cube: 6 maps, 256^2",
// "cascades: 3 maps, 1024^2 (lowered from 2048 to fit the map budget)".
std::string map_summary(const passes::LightShadowStats& stats);

// What the user set in the panel.
struct ViewerSettings {
  SceneOverrides overrides;
  float exposure = 1.0f;
  passes::ShadowOptions shadow_options;
  // The light whose receivers are tinted by the level their lookup reads (nullopt: none).
  std::optional<uint32_t> level_overlay;
};

// The last scene frame the viewer rendered.
struct FrameStats {
  uint64_t number = 0;  // 0: none yet
  double wall_ms = 0;   // build, record, submit and wait
  std::vector<rg::vulkan::PassTiming> passes;
  double gpu_ms() const;
};

// What the panel shows.
struct PanelView {
  live::LiveRenderer& live;
  const rg::CompiledPlan& plan;
  const FrameStats& frame;
  const TexelInspector& inspector;
  const std::vector<ImTextureID>& light_maps;  // one per light once a frame made them; may be empty
  CameraMode camera_mode;
  const std::string& status;  // e.g. where the last screenshot went
  Timeline& timeline;         // the panel plays, pauses, scrubs and sets its loop and rate
};

// What the user asked for this frame, besides the settings.
struct PanelRequests {
  bool scene_edited = false;            // settings.overrides changed
  bool shadow_options_changed = false;  // settings.shadow_options changed
  bool exposure_changed = false;
  bool level_overlay_changed = false;  // settings.level_overlay changed
  std::optional<std::string> load_scene;
  bool screenshot = false;
  bool reset_camera = false;
  std::optional<CameraMode> camera_mode;
  std::optional<std::pair<uint32_t, glm::uvec2>> inspect_light_texel;  // light, level-0 texel
  bool clear_inspection = false;
  bool time_changed = false;  // the timeline was scrubbed
};

class Panel {
 public:
  explicit Panel(const std::string& scene_file);
  // Draws the panel into `layout`'s panel column (placed there every frame, so a
  // window resize keeps it docked).
  PanelRequests draw(const PanelView& view, ViewerSettings& settings, const ViewLayout& layout);

 private:
  void draw_status(const PanelView& view, PanelRequests& requests);
  void draw_timeline(Timeline& timeline, const live::LiveRenderer& live, PanelRequests& requests);
  void draw_scene_file(PanelRequests& requests);
  void draw_lights(const PanelView& view, ViewerSettings& settings, PanelRequests& requests);
  void draw_media(const PanelView& view, ViewerSettings& settings, PanelRequests& requests);
  void draw_fog(const scene::Fog& fog, FogOverride& o, PanelRequests& requests);
  void draw_volume_scattering(const scene::Volume& volume, VolumeOverride& o, PanelRequests& requests);
  void draw_volume_shading(const scene::VolumeShading& shading, ViewerSettings& settings, PanelRequests& requests);
  void draw_display(const PanelView& view, ViewerSettings& settings, PanelRequests& requests);
  void draw_timings(const PanelView& view);
  void draw_memory(const PanelView& view);
  void draw_plan(const PanelView& view);
  void draw_inspection(const PanelView& view, PanelRequests& requests);

  std::string scene_file_;
  char scene_path_[1024] = {};
};

}  // namespace avsm::viewer
