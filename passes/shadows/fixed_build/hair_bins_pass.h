#pragma once
// Hair strand segments binned into a light's 8x8-texel tiles for the fixed-memory AVSM
// build (layout: shaders/shared/hair_bins.h). Four passes: "<prefix> hair bins clear"
// (tile words and the light's counter to 0), "... count" (per segment, every tile its
// ribbon's box overlaps), "... scan" (each tile's range in the entry buffer) and
// "... fill" (the segment indices). The entry buffer holds kHairBinEntriesPerSegment
// entries per segment: its size depends on the primitive count only, never on how many
// layers overlap. A tile whose range would not fit is marked and walks every segment
// in the build instead; the counter reports how many did. Shaders: hair_bins_*.comp.
#include <rendergraph/graph.h>

#include <string>

#include "gpu/pipeline.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_casters.h"

namespace avsm::passes {

struct HairBins {
  rg::BufferHandle tiles;    // kHairTileWords per tile
  rg::BufferHandle entries;  // segment indices, per tile one contiguous range
  rg::BufferHandle counter;  // the light's counter (kFixedCounter* words)
};

class HairBinsPass {
 public:
  HairBinsPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);
  // Bytes of the bins for `segment_count` segments on a `resolution`^2 map; the entries
  // stop at a storage buffer binding's reach (past it, tiles walk every segment, reported).
  static uint64_t tile_bytes(uint32_t resolution);
  static uint64_t entry_bytes(uint32_t segment_count, uint64_t max_storage_buffer_range);
  // Clears `counter` (16 bytes) and, with hair, bins it; without hair the bins are
  // empty (one tile word set, one entry).
  HairBins add_to_graph(rg::Graph& graph, const std::string& prefix, const LightView& light,
                        const StrandCasters& hair, rg::BufferHandle counter) const;

 private:
  void add_segment_pass(rg::Graph& graph, const std::string& name, const gpu::Pipeline& pipeline,
                                    HairBins& bins, const LightView& light, const StrandCasters& hair,
                                    bool writes_entries) const;
  gpu::Context& ctx_;
  gpu::Pipeline count_, scan_, fill_;
};

}  // namespace avsm::passes
