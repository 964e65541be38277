#include "passes/shadows/shadow_settings.h"

#include <algorithm>
#include <stdexcept>

#include "passes/shadows/capture/capture_lists.h"
#include "passes/shadows/techniques/techniques.h"
#include "shared/pages.h"
#include "shared/shadow.h"

namespace avsm::passes {

std::string light_display_name(const scene::Light& light, size_t index) {
  return "light " + std::to_string(index) + (light.name.empty() ? "" : " '" + light.name + "'");
}

void check_light_settings(const scene::Light& light, size_t index) {
  const std::string who = light_display_name(light, index);
  const scene::ShadowSettings& s = light.shadow;
  if (s.cascades < 1 || s.cascades > 4)
    throw std::invalid_argument(who + ": " + std::to_string(s.cascades) + " cascades; use 1 to 4");
  if (s.cascades > 1 && light.type != scene::LightType::directional)
    throw std::invalid_argument(who + ": cascades split a directional light's view; set shadow.cascades to 1 for a " +
                                std::string(scene::to_string(light.type)) + " light");
  if (s.cascades > 1 && s.fit != scene::ShadowFit::view)
    throw std::invalid_argument(who + ": cascades follow the camera; set shadow.fit to \"view\"");
  if (s.clusters < 0 || s.clusters > int(shared::kMaxClustersPerLight))
    throw std::invalid_argument(who + ": " + std::to_string(s.clusters) + " clusters; use 0 (off) to " +
                                std::to_string(shared::kMaxClustersPerLight));
  if (s.clusters > 1 && (light.type == scene::LightType::point || scene::is_area_light(light.type) || s.cascades > 1))
    throw std::invalid_argument(who + ": clustered maps are for directional and spot lights without cascades; "
                                "set shadow.clusters to 0");
  if (scene::is_area_light(light.type)) check_virtual_light_settings(light, who);
  if (s.nodes < 4 || s.nodes > 16 || s.nodes % 4 != 0)
    throw std::invalid_argument(who + ": " + std::to_string(s.nodes) + " AVSM nodes; use 4, 8, 12 or 16");
  if (s.kernel_radius < 1 || s.kernel_radius > int(shared::kMaxKernelRadius))
    throw std::invalid_argument(who + ": shadow kernel radius " + std::to_string(s.kernel_radius) + " texels; use 1 to " +
                                std::to_string(shared::kMaxKernelRadius));
  if (s.resolution < 1 || s.resolution > 16384)
    throw std::invalid_argument(who + ": shadow resolution " + std::to_string(s.resolution) + " is outside 1..16384");
  if (s.layout == scene::ShadowLayout::paged) check_paged_settings(light, who);
  check_shadow_settings(s, who);
}

// An area light's virtual lights' maps are built as one map from one set of capture
// lists, each a range of its texels (make_virtual_light_maps).
void check_virtual_light_settings(const scene::Light& light, const std::string& who) {
  const scene::ShadowSettings& s = light.shadow;
  if (light.virtual_lights < 1 || light.virtual_lights > int(shared::kMaxViewsPerLight))
    throw std::invalid_argument(who + ": " + std::to_string(light.virtual_lights) + " virtual lights; use 1 to " +
                                std::to_string(shared::kMaxViewsPerLight));
  if (s.build == scene::ShadowBuild::fixed)
    throw std::invalid_argument(who + ": an area light's virtual lights' maps are built together from capture lists; "
                                "set shadow.build to \"lists\"");
  const ShadowTechnique* technique = find_shadow_technique(s.technique);  // unknown ones: check_shadow_settings()
  if (technique && !technique->map_is_texel_ranges())
    throw std::invalid_argument(who + ": an area light's virtual lights share one map, which technique '" + s.technique +
                                "' cannot split; set shadow.technique to \"avsm\" (or another but \"dsm\")");
}

// What paged maps build today: AVSM from capture lists, one virtual map per light (six
// for a point light) that stays where the scene put it.
// (asks_for_dense_map() below lists the overrides these refusals turn into a dense map.)
void check_paged_settings(const scene::Light& light, const std::string& who) {
  const scene::ShadowSettings& s = light.shadow;
  auto refuse = [&](const std::string& why) {
    throw std::invalid_argument(who + ": shadow.layout \"paged\" " + why);
  };
  if (!pages_technique(s))
    refuse("builds AVSM maps, or keeps the uncompressed reference's lists; set shadow.technique to \"avsm\" or "
           "\"uncompressed\", or shadow.layout to \"dense\"");
  if (s.build != scene::ShadowBuild::lists)
    refuse("builds pages from capture lists; set shadow.build to \"lists\" or shadow.layout to \"dense\"");
  if (s.cascades > 1 || s.clusters > 1)
    refuse("replaces cascades and clusters with one virtual map; set shadow.cascades to 1 and shadow.clusters to 0");
  if (s.kernel != scene::ShadowKernel::none)
    refuse("matches texels to pixels instead of blurring them; set shadow.kernel to \"none\"");
  if (light.type == scene::LightType::directional && s.fit == scene::ShadowFit::view)
    refuse("keeps pages while the camera moves, so its map covers the scene; set shadow.fit to \"scene\"");
  if (scene::is_area_light(light.type))
    refuse("is not built for area lights yet (their virtual lights' maps are small and dense); set shadow.layout "
           "to \"dense\"");
  if (s.page_size != 32 && s.page_size != 64 && s.page_size != 128)
    refuse("pages are 32, 64 or 128 texels wide, not " + std::to_string(s.page_size) + "; set shadow.page_size");
  const int v = s.virtual_resolution;
  const int most = int(paged_max_virtual_resolution(light));
  if (v < 256 || v > most || (v & (v - 1)) != 0 || v < s.page_size)
    refuse("needs a virtual resolution that is a power of two, 256 to " + std::to_string(most) + " texels " +
           (most > 16384 ? "" : "(beyond 16384 for directional lights) ") + "and at least a page, not " +
           std::to_string(v) + "; set shadow.virtual_resolution");
  if (!(s.page_pool_mib > 0.0)) refuse("needs a page pool; set shadow.page_pool_mib above 0");
  if (s.page_builds_per_frame < 0) refuse("needs shadow.page_builds_per_frame of 0 (no limit) or more");
}

namespace {

// The overrides check_paged_settings() would refuse (for this light's type), and a map
// resolution: keep the two lists together.
bool asks_for_dense_map(const scene::ShadowOverrides& o, const scene::Light& light) {
  scene::ShadowSettings technique_only;
  if (o.technique) technique_only.technique = *o.technique;
  return (o.technique && find_shadow_technique(*o.technique) && !pages_technique(technique_only)) || o.resolution ||
         (o.kernel && *o.kernel != scene::ShadowKernel::none) || (o.build && *o.build == scene::ShadowBuild::fixed) ||
         (o.cascades && *o.cascades > 1 && light.type == scene::LightType::directional) ||
         (o.clusters && *o.clusters > 1 && light.type != scene::LightType::point && !scene::is_area_light(light.type)) ||
         (o.fit && *o.fit == scene::ShadowFit::view && light.type == scene::LightType::directional);
}

}  // namespace

void apply_shadow_overrides(const scene::ShadowOverrides& overrides, scene::Light& light) {
  const bool to_dense = !overrides.layout && light.shadow.layout == scene::ShadowLayout::paged &&
                        asks_for_dense_map(overrides, light);
  overrides.apply(light);
  if (!to_dense) return;
  light.shadow.layout = scene::ShadowLayout::dense;
  // Cascades split the camera's view: a paged sun covers the scene, its cascades do not.
  if (light.shadow.cascades > 1 && !overrides.fit) light.shadow.fit = scene::ShadowFit::view;
}

bool paged_keeps_lists(const scene::ShadowSettings& s) {
  const ShadowTechnique* technique = find_shadow_technique(s.technique);
  return technique != nullptr && technique->reads_capture_lists();
}

bool pages_technique(const scene::ShadowSettings& s) { return s.technique == "avsm" || paged_keeps_lists(s); }

uint64_t paged_list_segments_per_texel(const scene::ShadowSettings& s) {
  return uint64_t(shadow_technique("uncompressed").parameter(s, kPageSegmentsParameter));
}

uint64_t paged_list_slot_segments(const scene::ShadowSettings& s) {
  return uint64_t(s.page_size) * uint64_t(s.page_size) * paged_list_segments_per_texel(s);
}

uint64_t paged_slot_bytes(const scene::ShadowSettings& s) {
  const uint64_t texels = uint64_t(s.page_size) * uint64_t(s.page_size);
  if (paged_keeps_lists(s)) return texels * sizeof(uint32_t) + paged_list_slot_segments(s) * kCaptureSegmentBytes;
  return uint64_t(shared::page_slot_vec4s(uint32_t(s.page_size), uint32_t(s.nodes))) * 16;  // vec4s of 16 bytes
}

uint32_t paged_pool_slots(const scene::ShadowSettings& s, uint32_t maps) {
  const uint64_t pool = uint64_t(s.page_pool_mib * double(1 << 20)) / std::max(maps, 1u);
  return uint32_t(std::clamp<uint64_t>(pool / paged_slot_bytes(s), 1, 1u << 20));
}

uint32_t paged_window_pages(const scene::Light& light) {
  if (light.type != scene::LightType::directional || light.shadow.page_size <= 0) return 0;
  return kClipmapWindowTexels / uint32_t(light.shadow.page_size);
}

uint32_t paged_max_virtual_resolution(const scene::Light& light) {
  return light.type == scene::LightType::directional ? 262144u : 16384u;
}

uint32_t paged_fallback_level(const scene::ShadowSettings& s, uint32_t maps, uint32_t window) {
  const uint32_t virtual_res = uint32_t(s.virtual_resolution), page = uint32_t(s.page_size);
  const uint32_t levels = shared::page_level_count(virtual_res, page);
  uint32_t level = 0;
  while (level + 1 < levels && (virtual_res >> (level + 1)) >= uint32_t(s.resolution)) ++level;
  // The pages of `level` and every level above it, against the pool.
  const uint32_t slots = paged_pool_slots(s, maps);
  while (level + 1 < levels &&
         shared::page_table_entries(virtual_res, page, window) -
                 shared::page_table_level_first(virtual_res, page, window, level) >
             slots)
    ++level;
  return level;
}

}  // namespace avsm::passes
