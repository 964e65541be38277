#pragma once
// What ShadowMaps::finish_frame() measured of each light's last frame: the figures
// memory.json, report.html, the viewer's panel and the overflow warnings show.
// Kept apart from shadow_maps.h so the report (capture/frame_report.h) can hold
// them without the GPU headers.
#include <cstdint>
#include <optional>
#include <string>

#include "passes/shadows/pages/page_table.h"
#include "scene/light.h"

namespace avsm::passes {

// A deep shadow map's node pool: nodes the texels' compressed curves needed and the
// pool held; texels that did not fit read as unshadowed this frame (the pool grows
// for the next).
// Its build: the dispatches after the first that the frame made and that its longest
// list needed; cut short when it made fewer (texels whose build did not finish read as
// unshadowed; the next frame makes as many as were needed).
struct DsmPoolStats {
  uint64_t requested_nodes = 0, capacity_nodes = 0;
  bool overflowed = false;
  uint32_t build_dispatches = 0, needed_dispatches = 0;
  bool build_cut_short = false;
  bool held_by_budget = false;  // overflowed, and the map budget keeps the pool from growing
  bool operator==(const DsmPoolStats&) const = default;
};

// The fixed-memory build (scene::ShadowBuild::fixed): what it inserted and the transient
// memory it used, which depends on the map size and the hair segment count only.
struct FixedBuildStats {
  uint64_t inserted_segments = 0;   // opaque, hair and smoke segments that went into curves
  uint64_t light_depth_bytes = 0;   // the nearest-opaque depth image
  uint64_t hair_bin_bytes = 0;      // tile words + entry buffer
  uint64_t hair_bin_capacity = 0;   // entries the buffer holds
  uint64_t hair_bin_requested = 0;  // entries the segments asked for
  uint64_t tiles_walked = 0;        // tiles whose bin did not fit: they walked every segment
  uint64_t transient_bytes() const { return light_depth_bytes + hair_bin_bytes; }
  bool operator==(const FixedBuildStats&) const = default;
};

struct LightShadowStats {
  std::string light;
  std::string technique = "avsm";  // a name of passes/shadows/techniques/registry.h
  uint32_t nodes = 0, resolution = 0, mip_levels = 0;  // of each of its maps
  uint32_t maps = 1;                 // point lights: 6 faces; cascades; clusters
  std::string map_kind = "single";   // single, cube, cascades, clusters or virtual (a rect light's virtual lights)
  uint32_t lowered_from = 0;         // the resolution asked for, when the map budget lowered it; else 0
  uint64_t map_bytes = 0;               // persistent maps, all of the light's (0 for uncompressed)
  uint64_t capture_capacity = 0;        // segments the node buffer held this frame
  uint64_t capture_requested = 0;       // segments the captures asked for
  uint64_t capture_bytes = 0;           // heads + node buffer this frame
  bool overflowed = false;              // requested > capacity: segments were dropped
  bool page_slot_full = false;          // paged lists: a page's capture outgrew its slot (page_segments)
  uint64_t next_capture_capacity = 0;   // after growth
  std::optional<DsmPoolStats> dsm_pool;  // technique dsm only
  std::optional<FixedBuildStats> fixed_build;  // build fixed only (the lists above are then
                                               // only there for the uncompressed reference)
  // Layout paged only: its pages (summed over a point light's faces). The capture figures
  // above are then those of one page build.
  std::optional<PageStats> pages;
  // A buffer grows for the next frame: rendering again does better. Not a figure of
  // the frame, so not in memory.json.
  bool grew = false;

  // Some of the frame's shadowing was dropped: capture segments or pool nodes did not fit,
  // or a deep shadow map's build did not finish (lighter shadows this frame).
  bool dropped_shadowing() const {
    return overflowed || (dsm_pool && (dsm_pool->overflowed || dsm_pool->build_cut_short));
  }
  // Some of the frame's shadowing was lost: dropped, or receivers read coarser pages than
  // they asked for.
  bool lost_shadowing() const { return dropped_shadowing() || (pages && pages->pending > 0); }
  bool operator==(const LightShadowStats&) const = default;
};

}  // namespace avsm::passes
