#include "passes/avsm_mips_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/barriers.h"
#include "shared/passes/avsm_mips.h"

namespace avsm::passes {
namespace {

using Push = shared::AvsmMipsPush;  // shaders/shared/passes/avsm_mips.h

}  // namespace

AvsmMipsPass::AvsmMipsPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx), pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/avsm_mips.comp"), "avsm mips")) {}

rg::BufferHandle AvsmMipsPass::add_to_graph(rg::Graph& graph, const std::string& prefix, rg::BufferHandle map,
                                            const AvsmMapLayout& layout) const {
  if (layout.levels <= 1) return map;
  struct Data {
    rg::BufferHandle map;
  };
  const Data& data = graph.add_pass<Data>(prefix + " avsm mips", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& d) { d.map = b.read_write(map, rg::Usage::StorageReadWrite); },
      [this, layout](const Data& d, rg::PassContext& c) {
        VkCommandBuffer cmd = c.cmd();
        pipeline_.bind(cmd);
        gpu::Bindings(ctx_, pipeline_).buffer("AvsmMap", c.buffer(d.map)).push(cmd);
        for (uint32_t level = 1; level < layout.levels; ++level) {
          if (level > 1) {
            // The level just written is the next dispatch's source (same buffer, inside this pass).
            gpu::buffer_barrier(cmd, c.buffer(d.map), gpu::kComputeWrite,
                                {VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT,
                                 VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT});
          }
          pipeline_.push_constants(cmd, Push{uint32_t(layout.level_offset(level - 1)), layout.level_size(level - 1),
                                             uint32_t(layout.level_offset(level)), layout.level_size(level),
                                             layout.nodes});
          pipeline_.dispatch_threads(cmd, layout.level_size(level), layout.level_size(level));
        }
      });
  return data.map;
}

}  // namespace avsm::passes
