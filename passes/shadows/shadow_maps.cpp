// ShadowMaps: its lights and their maps, made from the scene or the caller's lights.
// The rest of the class, by responsibility:
//   shadow_maps_atlas.cpp    the budget, the atlas every map lives in, the looked-up lists
//   shadow_maps_views.cpp    each map's light view, fitted to the scene or the camera
//   shadow_maps_records.cpp  the frame's GpuShadow records and their upload
//   shadow_maps_graph.cpp    the frame's passes: captures, builds, list copies
//   shadow_maps_finish.cpp   a completed frame's figures, and growth for the next
#include "passes/shadows/shadow_maps.h"

#include <stdexcept>

#include "gpu/context.h"
#include "passes/shadows/techniques/techniques.h"

namespace avsm::passes {

ShadowMaps::ShadowMaps(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      capture_opaque_(ctx, shaders),
      capture_hair_(ctx, shaders),
      capture_smoke_(ctx, shaders),
      sort_(ctx, shaders),
      unshadowed_(ctx) {
  for (const ShadowTechnique* technique : shadow_techniques())
    builders_.push_back(technique->create_builder(ctx, shaders));
}

void ShadowMaps::set_scene(const scene::Scene& scene, const ShadowOptions& options) {
  // The scene's "shadows" block, under what the caller set.
  ShadowOptions merged = options;
  if (merged.map_budget_bytes == 0) merged.map_budget_bytes = uint64_t(scene.shadows.budget_mib * double(1 << 20));
  merged.fit_budget = merged.fit_budget || scene.shadows.fit_budget;
  std::vector<scene::Light> lights = scene.lights;
  for (scene::Light& light : lights)
    if (light.shadow.clusters == 0 && light.type != scene::LightType::point && !scene::is_area_light(light.type) &&
        light.shadow.cascades == 1)
      light.shadow.clusters = scene.shadows.clusters;
  try {
    set_lights(lights, scene.bounds, merged, scene_caster_objects(scene));
  } catch (const ShadowBudgetError& e) {
    throw ShadowBudgetError(scene.file.string() + ": " + e.what());
  } catch (const std::invalid_argument& e) {
    throw std::invalid_argument(scene.file.string() + ": " + e.what());
  }
}

void ShadowMaps::set_lights(const std::vector<scene::Light>& lights, const scene::Bounds& casters,
                            const ShadowOptions& options, const std::vector<CasterObject>& objects) {
  // (A paged level wider than the device's viewports is captured page by page with
  // cropped projections: page_view().)
  for (size_t i = 0; i < lights.size(); ++i) check_light_settings(lights[i], i);
  if (options.smoke_samples_per_segment < 1 || options.smoke_samples_per_segment > 255)
    throw std::invalid_argument("smoke capture: " + std::to_string(options.smoke_samples_per_segment) +
                                " samples per segment; use 1 to 255");
  // Frames in flight may use the buffers replaced here, and what finish_frame() reads of
  // them is per map as they declared it: the host finishes them first (the viewer's
  // LiveRenderer does), and then this wait costs nothing. Lights that only move do not
  // come here (place_light).
  vkDeviceWaitIdle(ctx_.device());
  retired_ = {};
  options_ = options;
  casters_ = casters;
  objects_ = objects;
  views_.clear();
  lights_.clear();
  maps_.clear();
  stats_.clear();
  for (size_t i = 0; i < lights.size(); ++i) {
    LightState state;
    state.light = lights[i];
    state.technique = &shadow_technique(lights[i].shadow.technique);
    lights_.push_back(std::move(state));
  }
  // Records: one per light first (what light_transmittance(i) reads), then the maps of
  // lights with several.
  record_count_ = uint32_t(lights_.size());
  for (uint32_t i = 0; i < lights_.size(); ++i) add_light_maps(i, casters, objects);
  fit_to_budget();
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    views_.push_back(maps_[lights_[i].first_map].view);
    LightShadowStats stats;
    stats.light = lights_[i].light.name.empty() ? "light " + std::to_string(i) : lights_[i].light.name;
    stats_.push_back(stats);
  }
  create_atlas();
  create_list_buffers();
  create_page_requests();
  // Views fitted to the camera as the last frame saw it, so that light_views() matches the
  // next frame's maps when nothing moves (the viewer inspects texels between frames).
  if (last_camera_) update_views(*last_camera_);
  unshadowed_.reserve(uint32_t(lights_.size()));
  const uint64_t entries = uint64_t(record_count_) * (options_.keep_reference ? 2 : 1);
  parameters_.create(ctx_, {std::max<uint64_t>(entries, 1) * sizeof(GpuShadow),
                            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                            gpu::MemoryLocation::DeviceLocal, "shadow parameters"});
}

void ShadowMaps::set_frames_in_flight(uint32_t count) {
  check_frames_in_flight(count);
  if (count == frames_in_flight()) return;
  vkDeviceWaitIdle(ctx_.device());  // frames in flight use the per-slot buffers replaced here
  retired_ = {};
  parameters_.set_frames(ctx_, count);
  for (MapState& map : maps_) create_frame_buffers(map);
  create_page_requests();
}

// The counters a frame's passes write for finish_frame(), and what it declared, per slot.
void ShadowMaps::create_frame_buffers(MapState& map) const {
  const VkBufferUsageFlags usage = VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  map.counter.set_frames(ctx_, frames_in_flight());
  map.counter.create(ctx_, {16, usage, gpu::MemoryLocation::HostReadback, map.prefix + " capture counter"});
  if (lights_[map.light].light.shadow.build == scene::ShadowBuild::fixed) {
    map.fixed_counter.set_frames(ctx_, frames_in_flight());
    map.fixed_counter.create(ctx_, {16, usage, gpu::MemoryLocation::HostReadback, map.prefix + " fixed build counter"});
  }
  if (map.pages) {
    map.page_counters.set_frames(ctx_, frames_in_flight());
  }
  map.declared.clear();
  map.declared.resize(frames_in_flight());
}

// A light's maps: one, six cube faces, a map per cascade or per caster cluster, or an
// area light's one map of its virtual lights' maps.
void ShadowMaps::add_light_maps(uint32_t index, const scene::Bounds& casters, const std::vector<CasterObject>& objects) {
  LightState& light = lights_[index];
  const scene::Light& l = light.light;
  const std::string name = "light " + std::to_string(index);
  // Each map's name, what it is fitted to, and (clusters) which casters it takes.
  std::vector<MapState> maps;
  auto add = [&](std::string prefix, const scene::Bounds& bounds) {
    MapState& map = maps.emplace_back();
    map.light = index;
    map.prefix = std::move(prefix);
    map.fit_bounds = bounds;
    return &map;
  };
  if (l.type == scene::LightType::point) {
    light.views = shared::kViewsCube;
    for (int face = 0; face < 6; ++face) add(name + " face " + std::to_string(face), casters)->face = face;
  } else if (scene::is_area_light(l.type)) {
    light.views = shared::kViewsVirtualLights;  // one map holds them all
    add(name + " virtual lights", casters);
  } else if (l.shadow.cascades > 1) {
    light.views = shared::kViewsCascades;  // update_views() fits each to the camera
    for (int c = 0; c < l.shadow.cascades; ++c) add(name + " cascade " + std::to_string(c), casters);
  } else if (l.shadow.clusters > 1) {
    const std::vector<CasterCluster> clusters = cluster_casters(l, objects, uint32_t(l.shadow.clusters));
    if (clusters.size() > 1) {
      light.views = shared::kViewsClusters;
      for (size_t c = 0; c < clusters.size(); ++c)
        add(name + " cluster " + std::to_string(c), clusters[c].bounds)->objects = clusters[c].objects;
    }
  }
  if (maps.empty()) {
    light.views = shared::kViewsSingle;
    add(name, casters);
  }
  light.first_map = uint32_t(maps_.size());
  light.map_count = uint32_t(maps.size());
  const std::shared_ptr<PageTable> pages = is_paged(light) ? create_page_table(light) : nullptr;
  for (MapState& map : maps) {
    map.record = light.views == shared::kViewsSingle ? index : record_count_++;
    if (light.views == shared::kViewsVirtualLights) {
      map.first_virtual_record = record_count_;
      record_count_ += uint32_t(l.virtual_lights);
    }
    map.map_state = initial_map_state(light);
    if (pages) create_page_state(map, pages);
    create_frame_buffers(map);
    // A paged map's lists are its pages' (a pool of them), kept for the reference only on request.
    map.lookups_read_lists = light.technique->reads_capture_lists() || has_reference(index);
    maps_.push_back(std::move(map));
    reset_view(maps_.back());
  }
}

}  // namespace avsm::passes
