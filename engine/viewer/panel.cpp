#include "viewer/panel.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <cstdio>
#include <cstring>

#include "capture/frame_outputs.h"
#include "capture/frame_report.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_settings.h"
#include "passes/shadows/techniques/techniques.h"

namespace avsm::viewer {

namespace {

constexpr std::array kFilters{scene::ShadowFilter::point, scene::ShadowFilter::bilinear,
                              scene::ShadowFilter::trilinear};
constexpr std::array kNodeCounts{4, 8, 12, 16};
constexpr std::array kResolutions{64, 128, 256, 512, 1024, 2048};
constexpr std::array kKernels{scene::ShadowKernel::none, scene::ShadowKernel::box, scene::ShadowKernel::gaussian};
constexpr std::array kCascadeCounts{1, 2, 3, 4};
constexpr std::array kClusterCounts{0, 2, 3, 4, 5, 6, 7, 8};

const ImVec4 kErrorColour{1.0f, 0.35f, 0.3f, 1.0f};
const ImU32 kReferenceColour = IM_COL32(235, 235, 235, 255);
const ImU32 kTechniqueColour = IM_COL32(230, 60, 50, 255);

std::string bytes_text(uint64_t bytes) {
  char text[32];
  if (bytes >= (1ull << 20))
    std::snprintf(text, sizeof(text), "%.1f MiB", double(bytes) / double(1ull << 20));
  else
    std::snprintf(text, sizeof(text), "%.1f KiB", double(bytes) / 1024.0);
  return text;
}

// A combo over `options`, labelled by `name`; returns the newly chosen one.
template <class T, class Options, class Name>
std::optional<T> choose(const char* label, const T& current, const Options& options, Name name) {
  std::optional<T> chosen;
  const std::string preview = name(current);
  if (ImGui::BeginCombo(label, preview.c_str())) {
    for (const T& option : options) {
      const bool selected = option == current;
      if (ImGui::Selectable(name(option).c_str(), selected) && !selected) chosen = option;
    }
    ImGui::EndCombo();
  }
  return chosen;
}

std::string technique_name(const std::string& t) { return t; }

// Every registered technique's name, in registry order.
const std::vector<std::string>& technique_names() {
  static const std::vector<std::string> names = [] {
    std::vector<std::string> out;
    for (const passes::ShadowTechnique* t : passes::shadow_techniques()) out.emplace_back(t->name());
    return out;
  }();
  return names;
}
std::string filter_name(scene::ShadowFilter f) { return std::string(scene::to_string(f)); }
std::string kernel_name(scene::ShadowKernel k) { return std::string(scene::to_string(k)); }
std::string number_name(int n) { return std::to_string(n); }

// The technique's curve (red) over the exact one (white) across the light's depth
// range, the stored AVSM nodes as dots and the picked point's depth as a line.
void plot_curve(const TexelCurve& curve) {
  const ImVec2 size(std::max(ImGui::GetContentRegionAvail().x, 120.0f), 140.0f);
  const ImVec2 origin = ImGui::GetCursorScreenPos();
  ImGui::InvisibleButton("curve", size);
  ImDrawList& draw = *ImGui::GetWindowDrawList();
  draw.AddRectFilled(origin, ImVec2(origin.x + size.x, origin.y + size.y), IM_COL32(25, 25, 30, 255));
  const float span = std::max(curve.far_depth - curve.near_depth, 1e-6f);
  auto at = [&](float depth, float t) {
    return ImVec2(origin.x + (depth - curve.near_depth) / span * size.x,
                  origin.y + (1.0f - std::clamp(t, 0.0f, 1.0f)) * size.y);
  };
  for (float t : {0.25f, 0.5f, 0.75f})
    draw.AddLine(at(curve.near_depth, t), at(curve.far_depth, t), IM_COL32(60, 60, 70, 255));
  auto polyline = [&](const std::vector<float>& values, ImU32 colour, float thickness) {
    std::vector<ImVec2> points;
    for (size_t i = 0; i < values.size() && i < curve.depths.size(); ++i) points.push_back(at(curve.depths[i], values[i]));
    draw.AddPolyline(points.data(), int(points.size()), colour, ImDrawFlags_None, thickness);
  };
  if (!curve.reference_values.empty()) polyline(curve.reference_values, kReferenceColour, 2.5f);
  polyline(curve.technique_values, kTechniqueColour, 1.5f);
  for (const capture::CurveNode& node : curve.nodes)
    if (node.depth >= curve.near_depth && node.depth <= curve.far_depth)
      draw.AddCircleFilled(at(node.depth, node.transmittance), 3.0f, kTechniqueColour);
  if (!std::isnan(curve.point_depth))
    draw.AddLine(at(curve.point_depth, 0.0f), at(curve.point_depth, 1.0f), IM_COL32(90, 160, 255, 255));
  if (ImGui::IsItemHovered()) {
    const float depth = curve.near_depth + (ImGui::GetIO().MousePos.x - origin.x) / size.x * span;
    const size_t k = size_t(std::clamp((depth - curve.near_depth) / span, 0.0f, 1.0f) * float(curve.depths.size() - 1));
    if (k < curve.reference_values.size())
      ImGui::SetTooltip("depth %.3f\n%s %.4f\nexact %.4f", curve.depths[k], curve.technique.c_str(),
                        curve.technique_values[k], curve.reference_values[k]);
    else if (k < curve.technique_values.size())
      ImGui::SetTooltip("depth %.3f\n%s %.4f", curve.depths[k], curve.technique.c_str(), curve.technique_values[k]);
  }
}

// On/off, sort, build, technique, nodes, resolution and filter: what every light has.
void draw_light_switches(const scene::Light& light, LightOverride& o, PanelRequests& requests) {
  const scene::ShadowSettings& shadow = light.shadow;
  bool on = o.enabled.value_or(true);
  if (ImGui::Checkbox("on", &on)) o.enabled = on, requests.scene_edited = true;
  ImGui::SameLine();
  bool sort = shadow.sort;
  if (ImGui::Checkbox("sort", &sort)) o.sort = sort, requests.scene_edited = true;
  ImGui::SameLine();
  // Paged maps build AVSM (or the uncompressed reference) from capture lists: untick
  // "paged maps" to change these.
  ImGui::BeginDisabled(shadow.layout == scene::ShadowLayout::paged);
  bool fixed = shadow.build == scene::ShadowBuild::fixed;
  if (ImGui::Checkbox("fixed-memory build", &fixed))
    o.build = fixed ? scene::ShadowBuild::fixed : scene::ShadowBuild::lists, requests.scene_edited = true;
  if (auto t = choose("technique", shadow.technique, technique_names(), technique_name))
    o.technique = *t, requests.scene_edited = true;
  ImGui::EndDisabled();
  if (auto n = choose("nodes", shadow.nodes, kNodeCounts, number_name)) o.nodes = *n, requests.scene_edited = true;
  if (auto r = choose("map resolution", shadow.resolution, kResolutions, number_name))
    o.resolution = *r, requests.scene_edited = true;
  if (auto f = choose("filter", shadow.filter, kFilters, filter_name)) o.filter = *f, requests.scene_edited = true;
}

// Direction (directional, spot), position (spot, point) and a point light's range.
void draw_light_placement(const scene::Light& light, LightOverride& o, PanelRequests& requests) {
  if (light.type != scene::LightType::point && light.type != scene::LightType::sphere) {
    glm::vec3 direction = light.direction;
    if (ImGui::DragFloat3("direction", &direction.x, 0.01f, -1.0f, 1.0f))
      o.direction = direction, requests.scene_edited = true;
  }
  if (light.type != scene::LightType::directional) {
    glm::vec3 position = light.position;
    if (ImGui::DragFloat3("position", &position.x, 0.02f)) o.position = position, requests.scene_edited = true;
  }
  if (light.type == scene::LightType::point) {
    if (light.range > 0.0f)
      ImGui::Text("range %.2f (light and shadows end there)", light.range);
    else
      ImGui::TextUnformatted("range: none (inverse-square falloff, shadowed over the scene)");
  }
}

// Dense or paged maps (docs/shadows.md, "Paged maps"), and a dense map's soft-shadow
// kernel. Paged maps build AVSM (or keep the uncompressed reference's lists) from capture
// lists only; ticking them also sets what they
// need (no kernel, no cascades or clusters, fitted to the scene), so the edit does not fail.
void draw_light_layout(const scene::Light& light, LightOverride& o, PanelRequests& requests) {
  const scene::ShadowSettings& shadow = light.shadow;
  bool paged = shadow.layout == scene::ShadowLayout::paged;
  const bool can_page = passes::pages_technique(shadow) && shadow.build == scene::ShadowBuild::lists;
  if (scene::is_area_light(light.type)) {  // one shared map of small maps, one per virtual light
    static constexpr std::array<scene::LightType, 3> kShapes = {scene::LightType::rect, scene::LightType::disk,
                                                                scene::LightType::sphere};
    if (auto shape = choose("shape", light.type, kShapes, [](scene::LightType t) { return std::string(scene::to_string(t)); }))
      o.area_shape = *shape, requests.scene_edited = true;
    if (light.type == scene::LightType::rect) {
      glm::vec2 size = light.size;
      if (ImGui::DragFloat2("size", &size.x, 0.01f, kMinAreaLightExtent, 100.0f))
        o.size = size, requests.scene_edited = true;
    } else {
      float radius = light.radius;
      if (ImGui::DragFloat("radius", &radius, 0.01f, kMinAreaLightExtent, 100.0f))
        o.radius = radius, requests.scene_edited = true;
    }
    int virtual_lights = light.virtual_lights;
    if (ImGui::SliderInt("virtual lights", &virtual_lights, 1, scene::kMaxVirtualLights))
      o.virtual_lights = virtual_lights, requests.scene_edited = true;
    ImGui::Text("each %u texels of the shared map%s",
                passes::virtual_light_tile_resolution(uint32_t(shadow.resolution), uint32_t(light.virtual_lights)),
                light.two_sided ? "; two-sided" : "");
    return;
  }
  ImGui::BeginDisabled(!paged && !can_page);
  if (ImGui::Checkbox("paged maps", &paged)) {
    o.layout = paged ? scene::ShadowLayout::paged : scene::ShadowLayout::dense;
    if (paged) {
      o.kernel = scene::ShadowKernel::none;
      o.cascades = 1;
      o.clusters = 0;
      if (light.type != scene::LightType::point) o.fit = scene::ShadowFit::scene;
    }
    requests.scene_edited = true;
  }
  ImGui::EndDisabled();
  if (!paged && !can_page && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("paged maps build AVSM (or keep the uncompressed reference's lists) from capture lists: set the "
                      "technique to avsm or uncompressed and untick the fixed-memory build");
  if (paged) return;  // pages match texels to pixels: no kernel
  if (auto k = choose("kernel", shadow.kernel, kKernels, kernel_name)) o.kernel = *k, requests.scene_edited = true;
}

// Shadow fit, cascades and clusters. The renderer refuses some combinations (cascades
// follow the camera, so they need fit view and exclude clusters); the panel disables
// the controls that would make one rather than let an edit fail.
void draw_light_fitting(const scene::Light& light, const scene::SceneShadows& scene_shadows, LightOverride& o,
                        PanelRequests& requests) {
  // A cube covers every way, and a rect light's virtual lights fit to the casters: nothing to fit.
  if (light.type == scene::LightType::point || scene::is_area_light(light.type)) return;
  const scene::ShadowSettings& shadow = light.shadow;
  const bool cascaded = shadow.cascades > 1, clustered = shadow.clusters > 1;
  // A paged map is one virtual map over the scene: no fitting to the view, no cascades
  // or clusters (untick "paged maps" for them).
  const bool paged = shadow.layout == scene::ShadowLayout::paged;
  ImGui::BeginDisabled(paged);

  int fit = shadow.fit == scene::ShadowFit::view ? 0 : 1;
  if (ImGui::RadioButton("fit view", &fit, 0)) o.fit = scene::ShadowFit::view, requests.scene_edited = true;
  ImGui::SameLine();
  ImGui::BeginDisabled(cascaded);
  if (ImGui::RadioButton("fit scene", &fit, 1)) o.fit = scene::ShadowFit::scene, requests.scene_edited = true;
  ImGui::EndDisabled();
  if (cascaded && ImGui::IsItemHovered(ImGuiHoveredFlags_AllowWhenDisabled))
    ImGui::SetTooltip("cascades follow the camera: set cascades to 1 first");

  if (light.type == scene::LightType::directional) {
    ImGui::BeginDisabled(clustered || shadow.fit == scene::ShadowFit::scene);
    if (auto c = choose("cascades", shadow.cascades, kCascadeCounts, number_name))
      o.cascades = *c, requests.scene_edited = true;
    ImGui::EndDisabled();
  }
  // 0 leaves the light to the scene's "shadows": {"clusters": N}, which the renderer
  // applies to lights without cascades.
  const auto cluster_name = [&](int n) {
    if (n == 0 && scene_shadows.clusters > 1) return "scene's (" + std::to_string(scene_shadows.clusters) + ")";
    return n <= 1 ? std::to_string(n) + " (off)" : std::to_string(n);
  };
  ImGui::BeginDisabled(cascaded);
  if (auto c = choose("clusters", shadow.clusters, kClusterCounts, cluster_name))
    o.clusters = *c, requests.scene_edited = true;
  ImGui::EndDisabled();
  ImGui::EndDisabled();  // paged
}

// The light's first map as the light sees it; a click on a texel plots its curve.
// Row 0 of the picture is the map's top row (texel y = resolution - 1).
void draw_light_map(ImTextureID texture, uint32_t light_index, const scene::Light& light,
                    const passes::LightShadowStats* stats, PanelRequests& requests) {
  const float side = std::min(ImGui::GetContentRegionAvail().x, 256.0f);
  const ImVec2 corner = ImGui::GetCursorScreenPos();
  ImGui::Image(texture, ImVec2(side, side));
  if (!ImGui::IsItemClicked(ImGuiMouseButton_Left)) return;
  // The map's own resolution: the budget may have lowered it below the settings'.
  const float res = float(stats && stats->resolution ? int(stats->resolution) : light.shadow.resolution);
  const ImVec2 mouse = ImGui::GetIO().MousePos;
  const uint32_t x = uint32_t(std::clamp((mouse.x - corner.x) / side * res, 0.0f, res - 1.0f));
  const uint32_t row = uint32_t(std::clamp((mouse.y - corner.y) / side * res, 0.0f, res - 1.0f));
  requests.inspect_light_texel = {{light_index, glm::uvec2(x, uint32_t(res) - 1 - row)}};
}

}  // namespace

std::string map_summary(const passes::LightShadowStats& stats) {
  std::string text = stats.maps == 1 ? stats.map_kind + " map"
                                      : stats.map_kind + ": " + std::to_string(stats.maps) + " maps";
  text += ", " + std::to_string(stats.resolution) + "^2";
  if (stats.lowered_from)
    text += " (lowered from " + std::to_string(stats.lowered_from) + " to fit the map budget)";
  return text;
}

double FrameStats::gpu_ms() const {
  double total = 0;
  for (const rg::vulkan::PassTiming& pass : passes) total += pass.gpu_ms;
  return total;
}

Panel::Panel(const std::string& scene_file) : scene_file_(scene_file) {
  std::snprintf(scene_path_, sizeof(scene_path_), "%s", scene_file.c_str());
}

PanelRequests Panel::draw(const PanelView& view, ViewerSettings& settings, const ViewLayout& layout) {
  PanelRequests requests;
  // Docked: the layout's column, every frame. ImGui's size 0 means "fit the contents",
  // and its windows are at least WindowMinSize (32x32): in a window under 80 pixels wide
  // the column is narrower than that, and the panel keeps to it all the same.
  const glm::vec2 position = layout.panel_position(), size = glm::max(layout.panel_size(), glm::vec2(1.0f));
  ImGui::SetNextWindowPos(ImVec2(position.x, position.y), ImGuiCond_Always);
  ImGui::SetNextWindowSize(ImVec2(size.x, size.y), ImGuiCond_Always);
  ImGui::PushStyleVar(ImGuiStyleVar_WindowMinSize, ImVec2(1.0f, 1.0f));
  ImGui::PushStyleVar(ImGuiStyleVar_WindowRounding, 0.0f);
  ImGui::Begin("AVSM viewer", nullptr,
               ImGuiWindowFlags_NoMove | ImGuiWindowFlags_NoResize | ImGuiWindowFlags_NoCollapse |
                   ImGuiWindowFlags_NoSavedSettings | ImGuiWindowFlags_NoBringToFrontOnFocus);
  ImGui::PopStyleVar(2);
  draw_status(view, requests);
  if (view.timeline.animated() && ImGui::CollapsingHeader("Timeline", ImGuiTreeNodeFlags_DefaultOpen))
    draw_timeline(view.timeline, view.live, requests);
  if (ImGui::CollapsingHeader("Texel inspection", ImGuiTreeNodeFlags_DefaultOpen)) draw_inspection(view, requests);
  if (ImGui::CollapsingHeader("Lights", ImGuiTreeNodeFlags_DefaultOpen)) draw_lights(view, settings, requests);
  if (ImGui::CollapsingHeader("GPU timings", ImGuiTreeNodeFlags_DefaultOpen)) draw_timings(view);
  if (ImGui::CollapsingHeader("Smoke and hair")) draw_media(view, settings, requests);
  if (ImGui::CollapsingHeader("Display")) draw_display(view, settings, requests);
  if (ImGui::CollapsingHeader("Memory")) draw_memory(view);
  if (ImGui::CollapsingHeader("Frame graph plan")) draw_plan(view);
  if (ImGui::CollapsingHeader("Scene file")) draw_scene_file(requests);
  ImGui::End();
  return requests;
}

// Play and pause, the playhead (frame and seconds), loop, and the frame rate it snaps to.
void Panel::draw_timeline(Timeline& timeline, const live::LiveRenderer& live, PanelRequests& requests) {
  if (ImGui::Button(timeline.playing() ? "pause" : "play")) timeline.playing() ? timeline.pause() : timeline.play();
  ImGui::SameLine();
  ImGui::Text("frame %d, %.3f s of %.3f s", timeline.frame(), double(timeline.time()), double(timeline.duration()));
  float time = timeline.time();
  if (ImGui::SliderFloat("time", &time, 0.0f, timeline.duration(), "%.3f s")) {
    timeline.scrub(time);
    requests.time_changed = true;
  }
  bool loop = timeline.loop();
  if (ImGui::Checkbox("loop", &loop)) timeline.set_loop(loop);
  ImGui::SameLine();
  float fps = timeline.fps();
  ImGui::SetNextItemWidth(80.0f);
  if (ImGui::InputFloat("fps", &fps, 0.0f, 0.0f, "%.0f", ImGuiInputTextFlags_EnterReturnsTrue)) {
    timeline.set_fps(fps);
    requests.time_changed = true;  // the playhead's frame is another instant at another rate
  }
  // Volume sequences: the file frame each shows (it lags the playhead while being read).
  for (const scene::VolumeSequence& sequence : live.scene().volume_sequences) {
    const std::optional<int> shown = live.sequence_frame(uint32_t(sequence.volume));
    ImGui::Text("%s: %s, file frame %s of %d-%d", live.scene().volumes[sequence.volume].name.c_str(),
                sequence.pattern.written.c_str(), shown ? std::to_string(*shown).c_str() : "-", sequence.timing.first,
                sequence.timing.last);
  }
}

void Panel::draw_status(const PanelView& view, PanelRequests& requests) {
  if (const std::optional<live::ReloadError>& error = view.live.error()) {
    ImGui::PushStyleColor(ImGuiCol_Text, kErrorColour);
    ImGui::TextWrapped("%s", error->summary().c_str());
    ImGui::PopStyleColor();
    if (ImGui::TreeNode("full message")) {
      ImGui::TextWrapped("%s", error->message.c_str());
      ImGui::TreePop();
    }
    ImGui::TextDisabled("still showing the last good version");
  }
  if (view.frame.number)
    ImGui::Text("frame %llu: %.1f ms (GPU %.1f ms)", (unsigned long long)view.frame.number, view.frame.wall_ms,
                view.frame.gpu_ms());
  if (ImGui::Button("Screenshot (F12)")) requests.screenshot = true;
  ImGui::SameLine();
  if (ImGui::Button("Reset camera")) requests.reset_camera = true;
  int mode = view.camera_mode == CameraMode::orbit ? 0 : 1;
  if (ImGui::RadioButton("orbit", &mode, 0)) requests.camera_mode = CameraMode::orbit;
  ImGui::SameLine();
  if (ImGui::RadioButton("fly (WASDQE)", &mode, 1)) requests.camera_mode = CameraMode::fly;
  if (!view.status.empty()) ImGui::TextWrapped("%s", view.status.c_str());
}

void Panel::draw_scene_file(PanelRequests& requests) {
  ImGui::InputText("file", scene_path_, sizeof(scene_path_));
  if (ImGui::Button("Load")) requests.load_scene = std::string(scene_path_);
  ImGui::SameLine();
  ImGui::TextDisabled("edits to the file and its assets reload by themselves");
}

void Panel::draw_lights(const PanelView& view, ViewerSettings& settings, PanelRequests& requests) {
  const scene::Scene& scene = view.live.scene();
  const std::vector<passes::LightShadowStats>& stats = view.live.renderer().shadows().frame_stats();
  for (size_t i = 0; i < scene.lights.size(); ++i) {
    const scene::Light& light = scene.lights[i];
    ImGui::PushID(int(i));
    const std::string title = "light " + std::to_string(i) + " '" + light.name + "' (" +
                              std::string(scene::to_string(light.type)) + ")";
    if (ImGui::TreeNode(title.c_str())) {
      LightOverride& o = settings.overrides.light(i);
      // Stats are per light of the last frame; after an edit that added or removed
      // lights they may not line up yet, so match them by name.
      const passes::LightShadowStats* light_stats =
          i < stats.size() && stats[i].light == light.name ? &stats[i] : nullptr;
      draw_light_switches(light, o, requests);
      draw_light_layout(light, o, requests);
      draw_light_placement(light, o, requests);
      draw_light_fitting(light, scene.shadows, o, requests);
      if (light_stats) ImGui::TextWrapped("%s", map_summary(*light_stats).c_str());
      if (i < view.light_maps.size()) draw_light_map(view.light_maps[i], uint32_t(i), light, light_stats, requests);
      ImGui::TreePop();
    }
    ImGui::PopID();
  }
}

// Multiple scattering's octaves (1: single scattering) and the sky's share of the smoke's light.
void Panel::draw_volume_scattering(const scene::Volume& volume, VolumeOverride& o, PanelRequests& requests) {
  scene::MultipleScattering m = volume.multiple_scattering;
  bool changed = ImGui::SliderInt("scattering octaves", &m.octaves, 1, 8);
  if (m.octaves > 1) {
    changed |= ImGui::SliderFloat("octave attenuation", &m.attenuation, 0.05f, 1.0f, "%.2f");
    changed |= ImGui::SliderFloat("octave contribution", &m.contribution, 0.0f, 1.0f, "%.2f");
  }
  if (changed) o.multiple_scattering = m, requests.scene_edited = true;
  float sky = volume.sky_light;
  if (ImGui::SliderFloat("sky light", &sky, 0.0f, 4.0f, "%.2f")) o.sky_light = sky, requests.scene_edited = true;
}

void Panel::draw_media(const PanelView& view, ViewerSettings& settings, PanelRequests& requests) {
  const scene::Scene& scene = view.live.scene();
  if (!scene.volumes.empty()) draw_volume_shading(scene.volume_shading, settings, requests);
  for (size_t i = 0; i < scene.volumes.size(); ++i) {
    const scene::Volume& volume = scene.volumes[i];
    ImGui::PushID(int(1000 + i));
    ImGui::Text("volume '%s'", volume.name.c_str());
    VolumeOverride& o = settings.overrides.volume(i);
    float extinction = volume.extinction_scale;
    if (ImGui::DragFloat("extinction scale", &extinction, std::max(extinction * 0.01f, 0.001f), 0.0f, 1e6f, "%.3f"))
      o.extinction_scale = extinction, requests.scene_edited = true;
    glm::vec3 albedo = volume.albedo;
    if (ImGui::ColorEdit3("albedo", &albedo.x)) o.albedo = albedo, requests.scene_edited = true;
    draw_volume_scattering(volume, o, requests);
    ImGui::PopID();
  }
  if (!scene.hair.empty()) {
    ImGui::Text("hair (%zu grooms): scales every strand", scene.hair.size());
    if (ImGui::SliderFloat("opacity x", &settings.overrides.hair_opacity_scale, 0.0f, 4.0f, "%.2f"))
      requests.scene_edited = true;
    if (ImGui::SliderFloat("width x", &settings.overrides.hair_width_scale, 0.1f, 10.0f, "%.2f",
                           ImGuiSliderFlags_Logarithmic))
      requests.scene_edited = true;
  }
  if (scene.volumes.empty() && scene.hair.empty()) ImGui::TextDisabled("the scene has no smoke or hair");
  draw_fog(scene.fog, settings.overrides.fog, requests);
}

// The fog's switch and its global medium (the boxes and the grid stay the file's).
void Panel::draw_fog(const scene::Fog& fog, FogOverride& o, PanelRequests& requests) {
  bool on = fog.enabled();
  if (ImGui::Checkbox("fog", &on)) o.enabled = on, requests.scene_edited = true;
  if (!on) return;
  ImGui::SameLine();
  ImGui::TextDisabled("%zu boxes", fog.boxes.size());
  float scattering = fog.global.scattering, absorption = fog.global.absorption;
  float g = fog.global.phase_g, sky = fog.sky_light;
  if (ImGui::SliderFloat("fog scattering /m", &scattering, 0.0f, 2.0f, "%.3f", ImGuiSliderFlags_Logarithmic))
    o.scattering = scattering, requests.scene_edited = true;
  if (ImGui::SliderFloat("fog absorption /m", &absorption, 0.0f, 2.0f, "%.3f", ImGuiSliderFlags_Logarithmic))
    o.absorption = absorption, requests.scene_edited = true;
  if (ImGui::SliderFloat("fog phase g", &g, -0.95f, 0.95f, "%.2f")) o.phase_g = g, requests.scene_edited = true;
  if (ImGui::SliderFloat("fog sky light", &sky, 0.0f, 4.0f, "%.2f")) o.sky_light = sky, requests.scene_edited = true;
}

// The scene's volume_shading (already overridden): how the camera sees the smoke.
void Panel::draw_volume_shading(const scene::VolumeShading& shading, ViewerSettings& settings,
                                PanelRequests& requests) {
  scene::VolumeShadingOverrides& o = settings.overrides.volume_shading;
  const char* modes[] = {"fast", "reference", "hidden"};
  int mode = int(shading.mode);
  if (ImGui::Combo("volume shading", &mode, modes, 3))
    o.mode = scene::VolumeShading::Mode(mode), requests.scene_edited = true;
  if (shading.mode != scene::VolumeShading::Mode::fast) return;
  const char* divisors[] = {"1 (full)", "2", "4"};
  int divisor = shading.resolution_divisor == 4 ? 2 : shading.resolution_divisor - 1;
  if (ImGui::Combo("march resolution 1/N", &divisor, divisors, 3))
    o.resolution_divisor = divisor == 2 ? 4 : divisor + 1, requests.scene_edited = true;
  float step = shading.step_voxels;
  if (ImGui::SliderFloat("march step (voxels)", &step, 0.125f, 4.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
    o.step_voxels = step, requests.scene_edited = true;
}

void Panel::draw_display(const PanelView& view, ViewerSettings& settings, PanelRequests& requests) {
  if (ImGui::SliderFloat("exposure", &settings.exposure, 0.05f, 16.0f, "%.2f", ImGuiSliderFlags_Logarithmic))
    requests.exposure_changed = true;
  // Receivers tinted by the level they read: red the finest, then orange, yellow, green,
  // cyan, blue, violet, magenta (shadow_level_overlay.comp).
  const std::vector<scene::Light>& lights = view.live.scene().lights;
  std::vector<int> overlay_options{-1};
  for (int i = 0; i < int(lights.size()); ++i) overlay_options.push_back(i);
  const int overlay = settings.level_overlay ? int(*settings.level_overlay) : -1;
  const auto overlay_name = [&](int i) {
    return i < 0 ? std::string("off") : lights[size_t(i)].name.empty() ? "light " + std::to_string(i) : lights[size_t(i)].name;
  };
  if (const std::optional<int> chosen = choose("shadow levels", overlay, overlay_options, overlay_name)) {
    settings.level_overlay = *chosen < 0 ? std::nullopt : std::optional<uint32_t>(uint32_t(*chosen));
    requests.level_overlay_changed = true;
  }
  if (ImGui::IsItemHovered())
    ImGui::SetTooltip("tints the light's receivers by the shadow map level they read: red level 0 (finest), then "
                      "orange, yellow, green, cyan, blue, violet, magenta; the rest is dimmed");
  if (ImGui::Checkbox("exponential interpolation", &settings.shadow_options.exponential_interpolation))
    requests.shadow_options_changed = true;
  if (ImGui::SliderFloat("normal offset (texels)", &settings.shadow_options.normal_offset_texels, 0.0f, 8.0f))
    requests.shadow_options_changed = true;
}

void Panel::draw_timings(const PanelView& view) {
  if (view.frame.passes.empty()) {
    ImGui::TextDisabled("no frame yet");
    return;
  }
  double longest = 0;
  for (const rg::vulkan::PassTiming& pass : view.frame.passes) longest = std::max(longest, pass.gpu_ms);
  if (ImGui::BeginTable("timings", 3, ImGuiTableFlags_RowBg | ImGuiTableFlags_SizingStretchProp)) {
    ImGui::TableSetupColumn("pass", ImGuiTableColumnFlags_WidthStretch, 3.0f);
    ImGui::TableSetupColumn("GPU ms", ImGuiTableColumnFlags_WidthFixed, ImGui::CalcTextSize("00000.00").x);
    ImGui::TableSetupColumn("", ImGuiTableColumnFlags_WidthStretch, 2.0f);
    ImGui::TableHeadersRow();
    for (const rg::vulkan::PassTiming& pass : view.frame.passes) {
      ImGui::TableNextRow();
      ImGui::TableNextColumn();
      ImGui::TextUnformatted(pass.name.c_str());
      ImGui::TableNextColumn();
      ImGui::Text("%.2f", pass.gpu_ms);
      ImGui::TableNextColumn();
      ImGui::ProgressBar(longest > 0 ? float(pass.gpu_ms / longest) : 0.0f, ImVec2(-1, 0), "");
    }
    ImGui::EndTable();
  }
  ImGui::Text("total %.2f ms GPU", view.frame.gpu_ms());
}

namespace {

// A paged light's pool: a bar of the pages asked for over its slots (the demand, which
// the bias keeps under about 85%; pages nobody asks for stay resident until their slot
// is needed, so the resident count alone fills up), and the frame's page figures
// (memory.json's "pages").
void draw_page_pool(const passes::PageStats& p) {
  const std::string label = std::to_string(p.requested) + " asked for, " + std::to_string(p.resident) +
                            " resident of " + std::to_string(p.slots) + " pages";
  ImGui::ProgressBar(p.slots > 0 ? std::min(float(p.requested) / float(p.slots), 1.0f) : 0.0f, ImVec2(-1, 0),
                     label.c_str());
  ImGui::Text("  pages built %u, invalidated %u, evicted %u, pending %u; bias %.2f%s", p.built, p.invalidated,
              p.evicted, p.pending, p.lod_bias, p.unserved > 0 ? " (pool full: coarser levels serve)" : "");
}

}  // namespace

// The figures memory.json and report.html show, from the same report types.
void Panel::draw_memory(const PanelView& view) {
  const capture::MemoryReport memory =
      capture::memory_report(view.plan, view.live.renderer(), view.live.scene(), /*frames_with_capture_overflow=*/0);
  ImGui::Text("transient: %s aliased in %llu heaps (%s without aliasing)",
              bytes_text(memory.transient_bytes_aliased).c_str(), (unsigned long long)memory.heap_count,
              bytes_text(memory.transient_bytes_unaliased).c_str());
  for (const passes::LightShadowStats& light : memory.lights) {
    ImGui::Text("%s: %s, %s; maps %s, capture %s", light.light.c_str(), light.technique.c_str(),
                map_summary(light).c_str(), bytes_text(light.map_bytes).c_str(), bytes_text(light.capture_bytes).c_str());
    ImGui::Text("  segments %llu of %llu%s", (unsigned long long)light.capture_requested,
                (unsigned long long)light.capture_capacity, light.overflowed ? " (overflowed: buffer grows)" : "");
    if (light.dsm_pool)
      ImGui::Text("  pool nodes %llu of %llu%s", (unsigned long long)light.dsm_pool->requested_nodes,
                  (unsigned long long)light.dsm_pool->capacity_nodes,
                  !light.dsm_pool->overflowed     ? ""
                  : light.dsm_pool->held_by_budget ? " (overflowed: the budget keeps its size)"
                                                   : " (overflowed: pool grows)");
    if (light.pages) draw_page_pool(*light.pages);
  }
}

void Panel::draw_plan(const PanelView& view) {
  const capture::PlanSummary plan = capture::plan_summary(view.plan);
  ImGui::Text("%zu passes, %u barriers, %zu culled", plan.passes.size(), plan.barrier_count, plan.culled_passes.size());
  for (size_t i = 0; i < plan.passes.size(); ++i) {
    const capture::PlanPassSummary& pass = plan.passes[i];
    ImGui::Text("%2zu %-8s %s (%zu barriers)", i, rg::to_string(pass.queue), pass.name.c_str(), pass.barrier_count);
  }
  for (const std::string& name : plan.culled_passes) ImGui::TextDisabled("   culled: %s", name.c_str());
}

void Panel::draw_inspection(const PanelView& view, PanelRequests& requests) {
  const TexelInspector& inspector = view.inspector;
  if (!inspector.active()) {
    ImGui::TextDisabled("click the view (or a light map) to plot a texel's transmittance curve");
    return;
  }
  if (ImGui::SmallButton("clear")) requests.clear_inspection = true;
  ImGui::SameLine();
  ImGui::TextWrapped("%s", inspector.description().c_str());
  if (inspector.curves().empty()) ImGui::TextDisabled("the point is outside every light's map");
  for (const TexelCurve& curve : inspector.curves()) {
    ImGui::PushID(int(curve.light));
    ImGui::Text("light %u '%s' texel (%u, %u): %s", curve.light, curve.light_name.c_str(), curve.texel.x,
                curve.texel.y, curve.technique.c_str());
    if (curve.has_values()) {
      if (curve.exact)
        ImGui::Text("max |T - T_exact| %.4f; white: exact, red: technique", curve.max_difference());
      else if (curve.level)
        ImGui::Text("paged: level %u's texel, red; no exact curve (pages keep no capture lists)", *curve.level);
      else
        ImGui::Text("paged: no resident page holds this texel");
      plot_curve(curve);
    } else {
      ImGui::TextDisabled("rendering...");
    }
    ImGui::PopID();
  }
}

}  // namespace avsm::viewer
