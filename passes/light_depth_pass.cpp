#include "passes/light_depth_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/rendering.h"
#include "shared/passes/light_depth.h"

namespace avsm::passes {

LightDepthPass::LightDepthPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) : ctx_(ctx) {
  gpu::GraphicsPipelineDesc desc;
  desc.name = "light depth";
  desc.vertex = shaders.load("shaders/passes/light_depth.vert");
  desc.depth_format = kFormat;
  desc.depth_test = desc.depth_write = true;
  desc.cull_mode = VK_CULL_MODE_NONE;
  pipeline_ = gpu::Pipeline::graphics(ctx, desc);
}

rg::TextureHandle LightDepthPass::add_to_graph(rg::Graph& graph, const std::string& prefix, const LightView& light,
                                               const MeshCasters& meshes) const {
  struct Data {
    rg::TextureHandle depth;
  };
  return graph.add_pass<Data>(prefix + " light depth", rg::QueueType::Graphics,
      [&](rg::PassBuilder& b, Data& d) {
        const rg::TextureDesc desc{light.resolution, light.resolution, 1, 1, 1, kFormat, kShadowResolutionSetting};
        d.depth = b.write(b.create_texture(prefix + " light depth", desc), rg::Usage::DepthAttachmentWrite);
      },
      [this, light, meshes](const Data& d, rg::PassContext& c) {
        VkCommandBuffer cmd = c.cmd();
        const gpu::DepthTarget depth{c.view(d.depth), c.layout(d.depth), 1.0f, /*store=*/true};
        gpu::begin_rendering(cmd, {light.resolution, light.resolution}, {}, &depth);
        if (!meshes.empty()) {
          pipeline_.bind(cmd);
          gpu::Bindings(ctx_, pipeline_).buffer("Vertices", meshes.vertices).push(cmd);
          pipeline_.push_constants(cmd, shared::LightDepthPush{light.light_from_world});
          vkCmdBindIndexBuffer(cmd, meshes.indices, 0, VK_INDEX_TYPE_UINT32);
          for (const MeshDraw& draw : meshes.draws)
            vkCmdDrawIndexed(cmd, draw.index_count, 1, draw.first_index, draw.vertex_offset, 0);
        }
        vkCmdEndRendering(cmd);
      })
      .depth;
}

}  // namespace avsm::passes
