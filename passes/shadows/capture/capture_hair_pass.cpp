#include "passes/shadows/capture/capture_hair_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/rendering.h"
#include "shared/passes/shadows/capture/capture_hair.h"

namespace avsm::passes {
namespace {

using Push = shared::CaptureHairPush;  // shaders/shared/passes/shadows/capture/capture_hair.h

}  // namespace

CaptureHairPass::CaptureHairPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) : ctx_(ctx) {
  gpu::GraphicsPipelineDesc desc;
  desc.name = "capture hair";
  desc.vertex = shaders.load("shaders/passes/shadows/capture/capture_hair.vert");
  desc.fragment = shaders.load("shaders/passes/shadows/capture/capture_hair.frag");
  desc.cull_mode = VK_CULL_MODE_NONE;
  pipeline_ = gpu::Pipeline::graphics(ctx, desc);
}

CaptureLists CaptureHairPass::add_to_graph(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                                           const std::vector<LightView>& views, const StrandCasters& hair) const {
  if (hair.empty()) return lists;
  return graph.add_pass<CaptureLists>(prefix + " capture hair", rg::QueueType::Graphics,
      [&](rg::PassBuilder& b, CaptureLists& d) { d = append_to_lists(b, lists); },
      [this, views, hair](const CaptureLists& d, rg::PassContext& c) {
        VkCommandBuffer cmd = c.cmd();
        // The same pipeline and buffers for every view (they outlast its rendering).
        pipeline_.bind(cmd);
        gpu::Bindings bindings(ctx_, pipeline_);
        bindings.buffer("Points", hair.points).buffer("Segments", hair.segments).buffer("Strands", hair.strands);
        bind_capture_lists(bindings, c, d);
        bindings.push(cmd);
        for (const LightView& light : views) {
          begin_light_rendering(cmd, light);
          const float resolution = float(light.raster());  // ribbon widths are in raster pixels
          pipeline_.push_constants(cmd, Push{light.light_from_world, glm::vec4(hair_ribbon_facing_point(light), 1.0f),
                                             {resolution, resolution}, glm::ivec2(light.raster_origin),
                                             light.depth_plane, {light.texel_size_base, light.texel_size_per_depth},
                                             light.list_tile()});
          vkCmdDraw(cmd, hair.segment_count * 6, 1, hair.first_segment * 6, 0);  // gl_VertexIndex counts from the first
          vkCmdEndRendering(cmd);
        }
      });
}

}  // namespace avsm::passes
