#pragma once
// What ShadowMaps::finish_frame() measured of each light's last frame: the figures
// memory.json, report.html, the viewer's panel and the overflow warnings show.
// Kept apart from shadow_maps.h so the report (capture/frame_report.h) can hold
// them without the GPU headers.
#include <cstdint>
#include <optional>
#include <string>

#include "scene/light.h"

namespace avsm::passes {

// A deep shadow map's node pool: nodes the texels' compressed curves needed and the
// pool held; texels that did not fit read as unshadowed this frame (the pool grows
// for the next).
struct DsmPoolStats {
  uint64_t requested_nodes = 0, capacity_nodes = 0;
  bool overflowed = false;
  bool operator==(const DsmPoolStats&) const = default;
};

struct LightShadowStats {
  std::string light;
  std::string technique = "avsm";  // a name of passes/techniques/registry.h
  uint32_t nodes = 0, resolution = 0, mip_levels = 0;
  uint64_t map_bytes = 0;               // persistent map (0 for uncompressed)
  uint64_t capture_capacity = 0;        // segments the node buffer held this frame
  uint64_t capture_requested = 0;       // segments the captures asked for
  uint64_t capture_bytes = 0;           // heads + node buffer this frame
  bool overflowed = false;              // requested > capacity: segments were dropped
  uint64_t next_capture_capacity = 0;   // after growth
  std::optional<DsmPoolStats> dsm_pool;  // technique dsm only
  // A buffer grows for the next frame: rendering again does better. Not a figure of
  // the frame, so not in memory.json.
  bool grew = false;

  // Some of the frame's shadowing was lost: capture segments or pool nodes did not fit.
  bool lost_shadowing() const { return overflowed || (dsm_pool && dsm_pool->overflowed); }
  bool operator==(const LightShadowStats&) const = default;
};

}  // namespace avsm::passes
