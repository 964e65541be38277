#include "passes/shadows/fixed_build/light_depth_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/rendering.h"
#include "shared/passes/shadows/fixed_build/light_depth.h"

namespace avsm::passes {

namespace {

gpu::Pipeline light_depth_pipeline(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, bool alpha_tested) {
  gpu::GraphicsPipelineDesc desc;
  desc.name = alpha_tested ? "light depth, alpha tested" : "light depth";
  desc.vertex = shaders.load("shaders/passes/shadows/fixed_build/light_depth.vert");
  if (alpha_tested) desc.fragment = shaders.load("shaders/passes/shadows/fixed_build/light_depth.frag");
  desc.depth_format = LightDepthPass::kFormat;
  desc.depth_test = desc.depth_write = true;
  desc.cull_mode = VK_CULL_MODE_NONE;
  return gpu::Pipeline::graphics(ctx, desc);
}

}  // namespace

LightDepthPass::LightDepthPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      depth_only_(light_depth_pipeline(ctx, shaders, false)),
      alpha_tested_(light_depth_pipeline(ctx, shaders, true)),
      alpha_(ctx) {}

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
        if (!meshes.empty()) record(cmd, light, meshes);
        vkCmdEndRendering(cmd);
      })
      .depth;
}

// Opaque draws first, depth only; then each draw that tests alpha with its texture.
void LightDepthPass::record(VkCommandBuffer cmd, const LightView& light, const MeshCasters& meshes) const {
  vkCmdBindIndexBuffer(cmd, meshes.indices, 0, VK_INDEX_TYPE_UINT32);
  shared::LightDepthPush push{light.light_from_world};
  depth_only_.bind(cmd);
  gpu::Bindings(ctx_, depth_only_).buffer("Vertices", meshes.vertices).push(cmd);
  depth_only_.push_constants(cmd, push);
  for (const MeshDraw& draw : meshes.draws)
    if (!draw.tests_alpha()) draw_mesh(cmd, draw);

  bool bound = false;
  for (const MeshDraw& draw : meshes.draws) {
    if (!draw.tests_alpha()) continue;
    if (!bound) alpha_tested_.bind(cmd);
    bound = true;
    gpu::Bindings bindings(ctx_, alpha_tested_);
    bindings.buffer("Vertices", meshes.vertices);
    alpha_.bind(bindings, draw);
    bindings.push(cmd);
    CasterAlphaTextures::set_push(push, draw);
    alpha_tested_.push_constants(cmd, push);
    draw_mesh(cmd, draw);
  }
}

}  // namespace avsm::passes
