#pragma once
// What a caller and the scene file set for the shadow maps: the options every light
// shares (ShadowOptions) and the check of each light's own shadow settings, which
// ShadowMaps::set_scene() and set_lights() run before anything is allocated.
#include <cstdint>
#include <string>

#include "passes/shadows/capture/capture_smoke_pass.h"
#include "scene/light.h"

namespace avsm::passes {

struct ShadowOptions {
  bool exponential_interpolation = false;
  float normal_offset_texels = 2.0f;           // receivers move this many texels along their normal
  uint64_t capture_limit_bytes = 128ull << 20;  // node buffer growth limit (lavapipe's maxStorageBufferRange)
  uint32_t smoke_samples_per_segment = CaptureSmokePass::kDefaultSamplesPerSegment;
  // Keep every light's capture lists to the end of the frame, so passes can look up
  // the exact (uncompressed) transmittance next to the technique's: every record has an
  // exact-reference record (GpuShadow::reference; reference_light_transmittance() in
  // shaders/common/shadow_lookup.glsl). Costs a copy of the lists for the whole frame.
  bool keep_reference = false;
  // With keep_reference, paged lights keep a reference too: each page's capture lists in
  // a slot of a pool of lists as many slots as the light's page pool (page_segments per
  // texel, the uncompressed technique's parameter). Far larger than the pages themselves,
  // so only captures that measure quality ask for it; without it paged lights have no
  // reference (has_reference(light)).
  bool keep_paged_reference = false;
  // Bytes all maps together may take (they share one atlas buffer); 0: the device's
  // storage buffer range, the most one binding can see. Checked before allocating.
  uint64_t map_budget_bytes = 0;
  // Over the budget: halve the resolution of the lights with the largest maps until
  // they fit (LightShadowStats::lowered_from says which) instead of failing.
  bool fit_budget = false;
  // Paged maps build every page their receivers ask for in the next frame, whatever
  // their shadow.page_builds_per_frame (captures, which must write converged maps).
  bool unlimited_page_builds = false;
  // Every page of this level of every paged map counts as asked for, frame after frame
  // (tests comparing a whole level with a dense map; -1: only what receivers ask for).
  int required_page_level = -1;
};

// Throws std::invalid_argument, naming light `index`, for shadow settings this build
// cannot render (cascades, clusters, nodes, kernel radius, resolution, the technique's
// own); set_scene() and set_lights() check every light with it.
void check_light_settings(const scene::Light& light, size_t index);

// The part of check_light_settings() for shadow.layout "paged" (`who` names the light).
void check_paged_settings(const scene::Light& light, const std::string& who);
// Throws std::invalid_argument naming `who` and the setting when an area light's
// virtual-light maps cannot be built from them.
void check_virtual_light_settings(const scene::Light& light, const std::string& who);

// Writes `overrides` (the capture's flags, a sweep job's, the viewer's edits) over
// `light`'s shadow settings (ShadowOverrides::apply(Light&)). An override that asks for
// what only a dense map has (a technique pages cannot hold, a map resolution, a kernel,
// the fixed build, cascades, clusters or a directional light fitted to the view) makes a
// paged light dense, unless it names the layout too: `avsm-capture --technique dsm` on a
// paged scene renders deep shadow maps rather than refusing, and `--shadow-res 64` means
// a 64^2 map rather than only a paged map's fallback level. With --shadow-layout paged
// it still refuses.
void apply_shadow_overrides(const scene::ShadowOverrides& overrides, scene::Light& light);

// Whether a paged map keeps its pages' capture lists (the uncompressed reference, whose
// lookups walk them) rather than AVSM curves.
bool paged_keeps_lists(const scene::ShadowSettings& s);
// Whether paged maps build the light's technique: AVSM, or the uncompressed reference's lists.
bool pages_technique(const scene::ShadowSettings& s);
// Capture segments one page of lists holds: the uncompressed technique's parameter
// "page_segments" per texel (passes/shadows/techniques/uncompressed/uncompressed.cpp),
// for its own paged maps and for a paged light's exact reference. Fixed with the pool,
// so a page whose capture asks for more is reported as overflowed, and built again when
// next asked for.
inline constexpr const char* kPageSegmentsParameter = "page_segments";
uint64_t paged_list_segments_per_texel(const scene::ShadowSettings& s);
uint64_t paged_list_slot_segments(const scene::ShadowSettings& s);
// The bytes of one page of a paged map: page_size^2 AVSM texels of shadow.nodes, or a
// page of capture lists (a head per texel and paged_list_slot_segments() segments).
uint64_t paged_slot_bytes(const scene::ShadowSettings& s);
// A paged light's pool in pages of each of its `maps` virtual maps (a point light's six
// faces split it evenly).
uint32_t paged_pool_slots(const scene::ShadowSettings& s, uint32_t maps);
// The coarsest level a paged map's receivers ask for: the one whose texels are those of a
// dense map of shadow.resolution, so that however far the pool's LOD bias goes, receivers
// read no coarser texels than the dense map has and an overflow never loses a shadow that
// map shows. The pool (of each of `maps` virtual maps) must hold that level and the ones
// above (of a clipmap level, its window: `window` pages per side); where it cannot, the
// finest coarser level it holds.
uint32_t paged_fallback_level(const scene::ShadowSettings& s, uint32_t maps, uint32_t window = 0);

// Texels per side of a clipmap level's window: a directional light's paged map covers
// the scene, and its levels finer than this keep only the pages around the camera
// (shared/pages.h). 4096 texels at the finest matched level span about 3x the distance
// from the camera to what it looks at, with a 60° field of view at 1280 pixels.
inline constexpr uint32_t kClipmapWindowTexels = 4096;
// Pages per side of a paged light's clipmap windows: directional lights'; 0 for others.
uint32_t paged_window_pages(const scene::Light& light);
// The largest virtual resolution of a light's paged map: a directional light's levels
// beyond the window are windows, so its table stays small; a whole level of 16384 texels
// in pages of 32 is a table of 350,000 words.
uint32_t paged_max_virtual_resolution(const scene::Light& light);

// "light 2 'key'": how messages name a light.
std::string light_display_name(const scene::Light& light, size_t index);

}  // namespace avsm::passes
