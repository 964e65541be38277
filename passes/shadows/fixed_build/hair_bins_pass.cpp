#include "passes/shadows/fixed_build/hair_bins_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>

#include "gpu/context.h"
#include "shared/hair_bins.h"
#include "shared/passes/shadows/fixed_build/hair_bins.h"

namespace avsm::passes {
HairBinsPass::HairBinsPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      count_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/shadows/fixed_build/hair_bins_count.comp"), "hair bins count")),
      scan_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/shadows/fixed_build/hair_bins_scan.comp"), "hair bins scan")),
      fill_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/shadows/fixed_build/hair_bins_fill.comp"), "hair bins fill")) {}

uint64_t HairBinsPass::tile_bytes(uint32_t resolution) {
  const uint64_t row = shared::hair_tiles_per_row(resolution);
  return row * row * shared::kHairTileWords * sizeof(uint32_t);
}

uint64_t HairBinsPass::entry_bytes(uint32_t segment_count, uint64_t max_storage_buffer_range) {
  const uint64_t wanted =
      std::max<uint64_t>(uint64_t(segment_count) * shared::kHairBinEntriesPerSegment, 1) * sizeof(uint32_t);
  return std::min(wanted, max_storage_buffer_range / sizeof(uint32_t) * sizeof(uint32_t));
}

HairBins HairBinsPass::add_to_graph(rg::Graph& graph, const std::string& prefix, const LightView& light,
                                    const StrandCasters& hair, rg::BufferHandle counter) const {
  const uint64_t entries = entry_bytes(hair.segment_count, ctx_.info().max_storage_buffer_range);
  HairBins bins = graph.add_pass<HairBins>(prefix + " hair bins clear", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, HairBins& d) {
        const rg::BufferDesc tiles{tile_bytes(light.resolution), kShadowResolutionSetting};
        d.tiles = b.write(b.create_buffer(prefix + " hair tiles", tiles), rg::Usage::TransferDst);
        d.entries = b.write(b.create_buffer(prefix + " hair bin entries", {entries}), rg::Usage::TransferDst);
        d.counter = b.write(counter, rg::Usage::TransferDst);
      },
      [](const HairBins& d, rg::PassContext& c) {
        vkCmdFillBuffer(c.cmd(), c.buffer(d.tiles), 0, VK_WHOLE_SIZE, 0);
        // Only the first entry: the fill writes every entry the build reads; the graph
        // must see the buffer written before the passes that read-modify it.
        vkCmdFillBuffer(c.cmd(), c.buffer(d.entries), 0, sizeof(uint32_t), 0);
        vkCmdFillBuffer(c.cmd(), c.buffer(d.counter), 0, VK_WHOLE_SIZE, 0);
      });
  if (hair.empty()) return bins;
  add_segment_pass(graph, prefix + " hair bins count", count_, bins, light, hair, false);
  bins = graph.add_pass<HairBins>(prefix + " hair bins scan", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, HairBins& d) {
        d = bins;
        d.tiles = b.read_write(bins.tiles, rg::Usage::StorageReadWrite);
        d.counter = b.read_write(bins.counter, rg::Usage::StorageReadWrite);
      },
      [this, light, entries](const HairBins& d, rg::PassContext& c) {
        scan_.bind(c.cmd());
        gpu::Bindings(ctx_, scan_)
            .buffer("HairTiles", c.buffer(d.tiles))
            .buffer("FixedBuildCounter", c.buffer(d.counter))
            .push(c.cmd());
        scan_.push_constants(c.cmd(), shared::HairBinsPush{light.light_from_world, {}, light.resolution, 0, 0,
                                                           shared::hair_tiles_per_row(light.resolution), uint32_t(entries / 4)});
        vkCmdDispatch(c.cmd(), 1, 1, 1);
      });
  add_segment_pass(graph, prefix + " hair bins fill", fill_, bins, light, hair, true);
  return bins;
}

// A pass of one thread per strand segment (count or fill), updating `bins`.
void HairBinsPass::add_segment_pass(rg::Graph& graph, const std::string& name, const gpu::Pipeline& pipeline,
                                    HairBins& bins, const LightView& light, const StrandCasters& hair,
                                    bool writes_entries) const {
  bins = graph.add_pass<HairBins>(name, rg::QueueType::Compute,
      [&](rg::PassBuilder& b, HairBins& d) {
        d = bins;
        d.tiles = b.read_write(bins.tiles, rg::Usage::StorageReadWrite);
        d.counter = b.read_write(bins.counter, rg::Usage::StorageReadWrite);
        if (writes_entries) d.entries = b.read_write(bins.entries, rg::Usage::StorageReadWrite);
      },
      [this, &pipeline, light, hair, writes_entries](const HairBins& d, rg::PassContext& c) {
        pipeline.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline);
        bindings.buffer("Points", hair.points)
            .buffer("Segments", hair.segments)
            .buffer("Strands", hair.strands)
            .buffer("HairTiles", c.buffer(d.tiles))
            .buffer("FixedBuildCounter", c.buffer(d.counter));
        if (writes_entries) bindings.buffer("HairBinEntries", c.buffer(d.entries));
        bindings.push(c.cmd());
        pipeline.push_constants(c.cmd(), shared::HairBinsPush{light.light_from_world,
                                                              glm::vec4(hair_ribbon_facing_point(light), 1.0f),
                                                              light.resolution, hair.first_segment, hair.segment_count,
                                                              shared::hair_tiles_per_row(light.resolution), 0});
        pipeline.dispatch_threads(c.cmd(), hair.segment_count, 1);
      });
}

}  // namespace avsm::passes
