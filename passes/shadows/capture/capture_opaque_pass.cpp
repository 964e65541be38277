#include "passes/shadows/capture/capture_opaque_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/rendering.h"
#include "shared/passes/shadows/capture/capture_opaque.h"

namespace avsm::passes {
namespace {

using Push = shared::CaptureOpaquePush;  // shaders/shared/passes/shadows/capture/capture_opaque.h

}  // namespace

void CaptureOpaquePass::bind(VkCommandBuffer cmd, rg::PassContext& c, const CaptureLists& lists,
                             const MeshCasters& meshes, const MeshDraw& draw) const {
  gpu::Bindings bindings(ctx_, pipeline_);
  bindings.buffer("Vertices", meshes.vertices);
  bind_capture_lists(bindings, c, lists);
  alpha_.bind(bindings, draw);
  bindings.push(cmd);
}

CaptureOpaquePass::CaptureOpaquePass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx), alpha_(ctx) {
  gpu::GraphicsPipelineDesc desc;
  desc.name = "capture opaque";
  desc.vertex = shaders.load("shaders/passes/shadows/capture/capture_opaque.vert");
  desc.fragment = shaders.load("shaders/passes/shadows/capture/capture_opaque.frag");
  desc.cull_mode = VK_CULL_MODE_NONE;
  pipeline_ = gpu::Pipeline::graphics(ctx, desc);
}

CaptureLists CaptureOpaquePass::add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                             const std::vector<LightView>& views, const MeshCasters& meshes) const {
  if (meshes.empty()) return lists;
  // The execute step copies the caster view: it runs when the executor records, after this returns.
  return graph.add_pass<CaptureLists>(prefix + " capture opaque", rg::QueueType::Graphics,
      [&](rg::PassBuilder& b, CaptureLists& d) { d = append_to_lists(b, lists); },
      [this, views, meshes](const CaptureLists& d, rg::PassContext& c) {
        VkCommandBuffer cmd = c.cmd();
        for (const LightView& light : views) {
          begin_light_rendering(cmd, light);
          pipeline_.bind(cmd);
          vkCmdBindIndexBuffer(cmd, meshes.indices, 0, VK_INDEX_TYPE_UINT32);
          Push push{light.light_from_world, light.depth_plane, {light.texel_size_base, light.texel_size_per_depth},
                    glm::ivec2(light.raster_origin), light.list_tile()};
          // Opaque draws first, under one binding; then each draw that tests alpha with its texture.
          bind(cmd, c, d, meshes, MeshDraw{});
          pipeline_.push_constants(cmd, push);
          for (const MeshDraw& draw : meshes.draws)
            if (!draw.tests_alpha()) draw_mesh(cmd, draw);
          for (const MeshDraw& draw : meshes.draws) {
            if (!draw.tests_alpha()) continue;
            bind(cmd, c, d, meshes, draw);
            CasterAlphaTextures::set_push(push, draw);
            pipeline_.push_constants(cmd, push);
            draw_mesh(cmd, draw);
          }
          vkCmdEndRendering(cmd);
        }
      });
}

}  // namespace avsm::passes
