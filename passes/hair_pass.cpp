#include "passes/hair_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/context.h"
#include "gpu/rendering.h"
#include "gpu/transfer.h"
#include "passes/opaque_pass.h"
#include "passes/shadow_maps.h"

namespace avsm::passes {

namespace {

// std430 mirrors of shaders/passes/hair.vert.
struct GpuStrand {
  glm::vec4 color_opacity;
  float width;
  float pad[3];
};
static_assert(sizeof(GpuStrand) == sizeof(StrandParameters));  // what StrandCasters document
struct HairPush {
  glm::mat4 view_projection;
  glm::vec4 camera_position;
  glm::vec2 viewport;
  uint32_t light_count;
  float pad;
};

}  // namespace

HairPass::HairPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) : ctx_(ctx) {
  gpu::GraphicsPipelineDesc desc;
  desc.name = "hair";
  desc.vertex = shaders.load("shaders/passes/hair.vert");
  desc.fragment = shaders.load("shaders/passes/hair.frag");
  desc.color_formats = {OpaquePass::kColorFormat};
  desc.depth_format = OpaquePass::kDepthFormat;
  desc.depth_test = true;
  desc.depth_write = false;
  desc.blend = gpu::BlendMode::PremultipliedAlpha;
  pipeline_ = gpu::Pipeline::graphics(ctx, desc);
}

void HairPass::set_scene(const scene::Scene& scene) {
  std::vector<glm::vec4> points;
  std::vector<glm::uvec2> segments;  // (first point, strand)
  std::vector<GpuStrand> strands;
  for (const scene::HairGroom& groom : scene.hair) {
    uint32_t point_base = uint32_t(points.size());
    for (const glm::vec3& p : groom.points) points.emplace_back(p, 1.0f);
    for (size_t s = 0; s < groom.strand_count(); ++s) {
      uint32_t strand = uint32_t(strands.size());
      strands.push_back({glm::vec4(groom.strand_color[s], groom.strand_opacity[s]), groom.strand_width[s], {}});
      for (uint32_t p = groom.strand_offsets[s]; p + 1 < groom.strand_offsets[s + 1]; ++p)
        segments.emplace_back(point_base + p, strand);
    }
  }
  segment_count_ = uint32_t(segments.size());
  points_ = gpu::create_buffer_from(ctx_, std::move(points), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "hair points");
  segments_ = gpu::create_buffer_from(ctx_, std::move(segments), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "hair segments");
  strands_ = gpu::create_buffer_from(ctx_, std::move(strands), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "hair strands");
}

rg::TextureHandle HairPass::add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                         const View& view, const gpu::Buffer& lights, uint32_t light_count,
                                         const ShadowInputs& shadows) {
  struct Targets {
    rg::TextureHandle color, depth;
  };
  const Targets& targets = graph.add_pass<Targets>("hair", rg::QueueType::Graphics,
      [&](rg::PassBuilder& b, Targets& d) {
        d.color = b.read_write(color, rg::Usage::ColorAttachment);
        d.depth = b.read(depth, rg::Usage::DepthAttachmentRead);
        shadows.declare_reads(b);
      },
      [this, view, &lights, light_count, shadows](const Targets& d, rg::PassContext& c) {
        if (segment_count_ == 0) return;
        VkCommandBuffer cmd = c.cmd();
        gpu::ColorTarget color_target{c.view(d.color), c.layout(d.color), {}, /*load=*/true};
        gpu::DepthTarget depth_target{c.view(d.depth), c.layout(d.depth), 1.0f, /*store=*/false, /*read_only=*/true};
        gpu::begin_rendering(cmd, {view.width, view.height}, {&color_target, 1}, &depth_target, /*flip_y=*/true);
        pipeline_.bind(cmd);
        gpu::Bindings bindings(ctx_, pipeline_);
        bindings.buffer(0, points_.handle())
            .buffer(1, segments_.handle())
            .buffer(2, strands_.handle())
            .buffer(3, lights.handle());
        shadows.bind(bindings, 4, c);
        bindings.push(cmd);
        pipeline_.push_constants(cmd, HairPush{view.view_projection, glm::vec4(view.camera_position, 1.0f),
                                               glm::vec2(view.width, view.height), light_count, 0.0f});
        vkCmdDraw(cmd, segment_count_ * 6, 1, 0, 0);
        vkCmdEndRendering(cmd);
      });
  return targets.color;
}

}  // namespace avsm::passes
