#include "passes/shadows/techniques/avsm/avsm_mips_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>

#include "gpu/context.h"
#include "passes/shadows/techniques/avsm/avsm_variants.h"
#include "shared/passes/shadows/techniques/avsm_mips.h"

namespace avsm::passes {
namespace {

using Push = shared::AvsmMipsPush;  // shaders/shared/passes/shadows/techniques/avsm_mips.h

constexpr uint64_t kVec4Bytes = 16;

// The bytes level `level`'s pass binds: level - 1 (read) and level (written), adjacent in
// the buffer, from the last offset at or before level - 1 that a storage buffer can be
// bound at. This is also what the pass declares to the graph: Vulkan (and synchronisation
// validation) sees a descriptor's whole range as accessed, not which bytes a shader reads.
rg::BufferRange level_window(const AvsmMapLayout& layout, uint32_t level, uint64_t offset_alignment) {
  const uint64_t alignment = std::max<uint64_t>(offset_alignment, 1);
  const uint64_t begin = layout.level_offset(level - 1) * kVec4Bytes / alignment * alignment;
  return {begin, layout.level_offset(level + 1) * kVec4Bytes - begin};
}

}  // namespace

AvsmMipsPass::AvsmMipsPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx), pipelines_(avsm_node_variants(ctx, shaders, "passes/shadows/techniques/avsm/avsm_mips.comp", "avsm mips")) {}

rg::BufferHandle AvsmMipsPass::add_to_graph(rg::Graph& graph, const std::string& prefix, rg::BufferHandle map,
                                            const AvsmMapLayout& layout, float near_depth, float far_depth) const {
  for (uint32_t level = 1; level < layout.levels; ++level)
    map = add_level(graph, prefix, map, layout, level, near_depth, far_depth);
  return map;
}

// One pass per level, building it from the level above inside its window of the buffer;
// the graph orders each window after the previous level's (a barrier on those bytes).
rg::BufferHandle AvsmMipsPass::add_level(rg::Graph& graph, const std::string& prefix, rg::BufferHandle map,
                                         const AvsmMapLayout& layout, uint32_t level, float near_depth,
                                         float far_depth) const {
  struct Data {
    rg::BufferHandle map;
  };
  const rg::BufferRange window = level_window(layout, level, ctx_.info().min_storage_buffer_offset_alignment);
  const uint32_t window_vec4 = uint32_t(window.offset / kVec4Bytes);  // offsets below count from the window
  const Data& data = graph.add_pass<Data>(prefix + " avsm mips level " + std::to_string(level), rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) { d.map = b.read_write(map, rg::Usage::StorageReadWrite, window); },
      [this, layout, level, window, window_vec4, near_depth, far_depth,
       &pipeline = pipelines_.get(layout.nodes)](const Data& d, rg::PassContext& c) {
        VkCommandBuffer cmd = c.cmd();
        pipeline.bind(cmd);
        gpu::Bindings(ctx_, pipeline).buffer("AvsmMap", {c.buffer(d.map).buffer, window.size, c.buffer(d.map).offset + window.offset}).push(cmd);
        pipeline.push_constants(cmd, Push{uint32_t(layout.level_offset(level - 1)) - window_vec4,
                                           layout.level_size(level - 1),
                                           uint32_t(layout.level_offset(level)) - window_vec4, layout.level_size(level),
                                           layout.nodes, near_depth, far_depth});
        pipeline.dispatch_threads(cmd, layout.level_size(level), layout.level_size(level));
      });
  return data.map;
}

}  // namespace avsm::passes
