// ShadowMaps' light views: where each map looks from, fitted to the scene's bounds, or
// to the camera for directional lights that follow it (fit view, cascades).
#include <algorithm>

#include "passes/shadows/shadow_maps.h"

namespace avsm::passes {

void ShadowMaps::place_light(uint32_t index, const glm::vec3& position, const glm::vec3& direction) {
  LightState& light = lights_.at(index);
  light.light.position = position;
  light.light.direction = direction;
  for (uint32_t m = light.first_map; m < light.first_map + light.map_count; ++m) reset_view(maps_[m]);
  // Every page (every face's: they share the table) saw the light from where it was.
  if (maps_[light.first_map].pages) maps_[light.first_map].pages->invalidate_all();
  // Maps fitted to the camera are fitted again by the next frame (update_views).
  views_[index] = maps_[light.first_map].view;
}

// A map's view before any camera is known (update_views() fits the camera's); an area
// light's map: the shared map's, and its virtual lights' views.
void ShadowMaps::reset_view(MapState& map) const {
  const LightState& light = lights_[map.light];
  if (light.views != shared::kViewsVirtualLights) {
    map.view = initial_view(map);
    return;
  }
  VirtualLightMaps virtual_maps =
      make_virtual_light_maps(light.light, map.fit_bounds, uint32_t(light.light.shadow.resolution));
  map.view = virtual_maps.shared;
  map.virtual_views = std::move(virtual_maps.views);
}

LightView ShadowMaps::initial_view(const MapState& map) const {
  const LightState& light = lights_[map.light];
  const scene::ShadowSettings& s = light.light.shadow;
  const uint32_t resolution = uint32_t(is_paged(light) ? s.virtual_resolution : s.resolution);  // paged: the virtual map
  if (map.face >= 0)  // paged: the guard texels of its coarsest level, one page
    return make_point_face_view(light.light, uint32_t(map.face), casters_, resolution,
                                is_paged(light) ? uint32_t(s.page_size) : 0u);
  return make_light_view(light.light, map.fit_bounds, resolution);
}

// Maps fitted to the camera follow it: a directional light's (fit view) and its cascades.
void ShadowMaps::update_views(const View& camera) {
  last_camera_ = camera;
  for (LightState& light : lights_) {
    const scene::Light& l = light.light;
    if (l.type != scene::LightType::directional || l.shadow.fit != scene::ShadowFit::view) continue;
    if (light.views == shared::kViewsClusters) continue;  // fitted to their clusters
    const float far = l.shadow.distance > 0.0f ? std::min(l.shadow.distance, camera.far_plane) : camera.far_plane;
    const uint32_t resolution = uint32_t(l.shadow.resolution);
    if (light.views == shared::kViewsCascades) {
      light.cascade_ends = cascade_ends(camera.near_plane, far, light.map_count);
      float begin = camera.near_plane;
      for (uint32_t c = 0; c < light.map_count; ++c) {
        const float end = light.cascade_ends[c];
        maps_[light.first_map + c].view = make_fitted_directional_view(l, casters_, resolution, camera_slice(camera, begin, end));
        // The next cascade starts where this one's blend band does, so both cover the band.
        begin = end - (end - begin) * l.shadow.cascade_blend;
      }
    } else {
      maps_[light.first_map].view = make_fitted_directional_view(l, casters_, resolution, camera_slice(camera, camera.near_plane, far));
    }
  }
  for (uint32_t i = 0; i < lights_.size(); ++i) views_[i] = maps_[lights_[i].first_map].view;
  move_page_windows(camera);
}

// A directional light's paged map keeps its finest levels as windows around the camera
// (shared/pages.h): they follow it, in whole pages.
void ShadowMaps::move_page_windows(const View& camera) {
  for (const LightState& light : lights_) {
    MapState& map = maps_[light.first_map];
    if (!map.pages || map.pages->window_pages() == 0) continue;
    // A directional light's projection is orthographic: every point has a uv.
    const glm::vec2 uv = glm::clamp(map.view.uv(camera.camera_position).value_or(glm::vec2(0.5f)), 0.0f, 1.0f);
    const uint32_t last = map.pages->virtual_resolution() - 1;
    map.pages->move_window(glm::min(glm::uvec2(uv * float(map.pages->virtual_resolution())), glm::uvec2(last)));
  }
}

uint32_t ShadowMaps::lookups_per_point() const {
  uint32_t lookups = 0;
  for (const LightState& light : lights_) {
    if (light.views == shared::kViewsVirtualLights) lookups += uint32_t(maps_[light.first_map].virtual_views.size());
    else if (light.views == shared::kViewsClusters) lookups += light.map_count;
    else lookups += light.views == shared::kViewsCascades ? 2u : 1u;  // a split blends two cascades
  }
  return std::max(lookups, 1u);
}

std::vector<LightView> ShadowMaps::map_views(uint32_t light) const {
  std::vector<LightView> views;
  const LightState& l = lights_.at(light);
  for (uint32_t m = l.first_map; m < l.first_map + l.map_count; ++m) {
    if (!maps_[m].virtual_views.empty()) return maps_[m].virtual_views;
    views.push_back(maps_[m].view);
  }
  return views;
}

}  // namespace avsm::passes
