// ShadowMaps after a frame completed: its figures per map and light (LightShadowStats),
// and what grows for the next frame (capture lists, a technique's map).
#include <algorithm>
#include <cstring>
#include <stdexcept>

#include "gpu/context.h"
#include "passes/shadows/fixed_build/hair_bins_pass.h"
#include "passes/shadows/fixed_build/light_depth_pass.h"
#include "passes/shadows/shadow_maps.h"
#include "shared/hair_bins.h"

namespace avsm::passes {

FixedBuildStats ShadowMaps::fixed_build_stats(const MapState& map, uint32_t slot) const {
  uint32_t counters[4] = {0, 0, 0, 0};  // kFixedCounter* (shared/hair_bins.h)
  std::memcpy(counters, map.fixed_counter[slot].mapped(), sizeof(counters));
  const DeclaredMap& declared = map.declared[slot];
  const uint32_t resolution = declared.map_state.layout.resolution;
  FixedBuildStats f;
  f.inserted_segments = counters[shared::kFixedCounterInserted];
  const uint64_t entry_bytes = HairBinsPass::entry_bytes(declared.hair_segments, ctx_.info().max_storage_buffer_range);
  f.light_depth_bytes = LightDepthPass::bytes(resolution);
  f.hair_bin_capacity = declared.hair_segments == 0 ? 0 : entry_bytes / sizeof(uint32_t);
  f.hair_bin_bytes = HairBinsPass::tile_bytes(resolution) + entry_bytes;
  f.hair_bin_requested = counters[shared::kFixedCounterBinEntries];
  f.tiles_walked = counters[shared::kFixedCounterTilesWalked];
  return f;
}

// One map's figures of the frame completed in `slot`, read against what that frame
// declared; grows its capture (and the technique's state) for the next frame declared,
// from what later frames already have. Sets `remake` when the atlas or the list buffers
// must be made again.
LightShadowStats ShadowMaps::finish_map(MapState& map, uint32_t slot, bool& remake) {
  const LightState& light = lights_[map.light];
  const DeclaredMap& declared = map.declared[slot];
  LightShadowStats stats;
  if (map.pages) {
    stats.technique = light.light.shadow.technique;
    stats.nodes = declared.map_state.layout.nodes;
    stats.resolution = map.pages->virtual_resolution();
    stats.mip_levels = map.pages->levels();
    finish_pages(map, slot, stats);
    return stats;
  }
  uint32_t counters[3] = {0, 0, 0};  // capture segments, what the technique's build asked for
  if (declared.captured_lists) std::memcpy(counters, map.counter[slot].mapped(), sizeof(counters));
  const uint32_t requested = counters[0];
  const AvsmMapLayout& layout = declared.map_state.layout;
  stats.technique = light.light.shadow.technique;
  stats.nodes = layout.nodes;
  stats.resolution = layout.resolution;
  stats.mip_levels = layout.levels;
  stats.capture_capacity = declared.capacity;
  stats.capture_requested = requested;
  const uint64_t texels = uint64_t(layout.resolution) * layout.resolution;
  stats.capture_bytes = declared.captured_lists ? declared.capacity * kCaptureSegmentBytes + texels * 4 : 0;
  if (light.light.shadow.build == scene::ShadowBuild::fixed) stats.fixed_build = fixed_build_stats(map, slot);
  stats.overflowed = requested > declared.capacity;
  if (requested > map.capacity) {
    const uint64_t limit = options_.capture_limit_bytes / kCaptureSegmentBytes;
    const uint64_t grown = std::min(limit, round_up(requested + requested / 4, 1024));
    // The capture lists are transient, sized by each frame's graph; only the copies
    // that lookups read are buffers of this size.
    remake = remake || (grown > map.capacity && map.lookups_read_lists);
    map.capacity = std::max(map.capacity, grown);
  }
  stats.next_capture_capacity = map.capacity;
  stats.grew = stats.next_capture_capacity > stats.capture_capacity;
  // The technique's figures against the state the frame had; its next state from the current one.
  TechniqueMapState as_declared = declared.map_state;
  if (light.technique->finish_frame(counters, as_declared, stats)) stats.grew = true;  // a larger map next frame
  LightShadowStats against_current;
  if (light.technique->finish_frame(counters, map.map_state, against_current)) remake = true;
  return stats;
}

namespace {

// Figures of a light's several maps as one: sums, and whether any lost shadowing.
void add_map_stats(LightShadowStats& light, const LightShadowStats& map) {
  light.technique = map.technique;
  light.nodes = map.nodes;
  light.resolution = map.resolution;
  light.mip_levels = map.mip_levels;
  light.capture_capacity += map.capture_capacity;
  light.capture_requested += map.capture_requested;
  light.capture_bytes += map.capture_bytes;
  light.overflowed = light.overflowed || map.overflowed;
  light.page_slot_full = light.page_slot_full || map.page_slot_full;
  light.next_capture_capacity += map.next_capture_capacity;
  light.grew = light.grew || map.grew;
  if (map.dsm_pool) {
    DsmPoolStats pool = light.dsm_pool.value_or(DsmPoolStats{});
    pool.requested_nodes += map.dsm_pool->requested_nodes;
    pool.capacity_nodes += map.dsm_pool->capacity_nodes;
    pool.overflowed = pool.overflowed || map.dsm_pool->overflowed;
    pool.build_dispatches = std::max(pool.build_dispatches, map.dsm_pool->build_dispatches);
    pool.needed_dispatches = std::max(pool.needed_dispatches, map.dsm_pool->needed_dispatches);
    pool.build_cut_short = pool.build_cut_short || map.dsm_pool->build_cut_short;
    pool.held_by_budget = pool.held_by_budget || map.dsm_pool->held_by_budget;
    light.dsm_pool = pool;
  }
  if (map.pages) {
    PageStats pages = light.pages.value_or(PageStats{});
    const PageStats& m = *map.pages;
    pages.slots += m.slots;
    pages.requested += m.requested;
    pages.resident += m.resident;
    pages.built += m.built;
    pages.invalidated += m.invalidated;
    pages.evicted += m.evicted;
    pages.pending += m.pending;
    pages.unserved += m.unserved;
    pages.lod_bias = std::max(pages.lod_bias, m.lod_bias);
    pages.settling = pages.settling || m.settling;
    light.pages = pages;
  }
  if (map.fixed_build) {
    FixedBuildStats f = light.fixed_build.value_or(FixedBuildStats{});
    f.inserted_segments += map.fixed_build->inserted_segments;
    f.light_depth_bytes = std::max(f.light_depth_bytes, map.fixed_build->light_depth_bytes);  // transient, aliased
    f.hair_bin_bytes = std::max(f.hair_bin_bytes, map.fixed_build->hair_bin_bytes);
    f.hair_bin_capacity = std::max(f.hair_bin_capacity, map.fixed_build->hair_bin_capacity);
    f.hair_bin_requested += map.fixed_build->hair_bin_requested;
    f.tiles_walked += map.fixed_build->tiles_walked;
    light.fixed_build = f;
  }
}

}  // namespace

void ShadowMaps::finish_frame(uint32_t slot) {
  if (slot >= frames_in_flight())
    throw std::invalid_argument("ShadowMaps::finish_frame: frame slot " + std::to_string(slot) + " of " +
                                std::to_string(frames_in_flight()) + " frames in flight");
  retired_.finished(slot);
  bool remake = false;
  std::vector<LightShadowStats> per_light(lights_.size());
  std::vector<TechniqueMapState> before;
  for (const MapState& map : maps_) before.push_back(map.map_state);
  for (MapState& map : maps_) map.stats = finish_map(map, slot, remake);
  // Maps that grew (deep shadow map pools) stay within the budget: past it they keep
  // their size, and the frames go on reporting what did not fit. Such a map did not
  // grow, so rendering again does not help it (its build dispatches still may).
  if (atlas_bytes_needed() > map_budget())
    for (size_t m = 0; m < maps_.size(); ++m) {
      MapState& map = maps_[m];
      if (map.map_state.pool_nodes == before[m].pool_nodes) continue;
      map.map_state.pool_nodes = before[m].pool_nodes;
      LightShadowStats& stats = map.stats;
      stats.dsm_pool->held_by_budget = true;
      stats.grew = stats.next_capture_capacity > stats.capture_capacity || stats.dsm_pool->build_cut_short;
    }
  for (const MapState& map : maps_) add_map_stats(per_light[map.light], map.stats);
  if (remake) {
    // For the next frame. The frames still in flight bind the buffers replaced here (a
    // grown technique map, the looked-up lists: the uncompressed technique and the exact
    // reference): they keep them until they finish.
    for (gpu::Buffer* replaced : {&atlas_, &list_heads_, &list_nodes_}) retired_.retire(std::move(*replaced));
    create_list_buffers();
    create_atlas();
    // The new buffers hold none of the pages the tables list: every page is built again.
    for (const LightState& light : lights_)
      if (maps_[light.first_map].pages) maps_[light.first_map].pages->invalidate_all();
  }
  for (uint32_t i = 0; i < lights_.size(); ++i) {
    LightShadowStats& stats = per_light[i];
    const LightState& light = lights_[i];
    stats.light = stats_[i].light;
    stats.maps = light.views == shared::kViewsVirtualLights ? uint32_t(maps_[light.first_map].virtual_views.size())
                                                            : light.map_count;
    stats.map_kind = light.views == shared::kViewsCube        ? "cube"
                     : light.views == shared::kViewsCascades  ? "cascades"
                     : light.views == shared::kViewsClusters  ? "clusters"
                     : light.views == shared::kViewsVirtualLights ? "virtual"
                                                              : "single";
    stats.lowered_from = light.lowered_from;
    for (uint32_t m = light.first_map; m < light.first_map + light.map_count; ++m)
      stats.map_bytes += maps_[m].map ? maps_[m].map.size() : 0;  // after a pool growth: the new map
    const MapState& first = maps_[light.first_map];
    if (first.pages && first.lookups_read_lists)  // a pool of pages of lists, in the list buffers
      stats.map_bytes += first.list_heads.size() + first.list_nodes.size();
    stats_[i] = stats;
  }
}

}  // namespace avsm::passes
