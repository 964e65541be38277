#include "passes/camera/hair/hair_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>

#include "gpu/context.h"
#include "gpu/rendering.h"
#include "gpu/transfer.h"
#include "passes/camera/surfaces/opaque_pass.h"
#include "passes/shadows/shadow_maps.h"
#include "shared/passes/camera/hair/hair.h"
#include "passes/frame/frame_inputs.h"

namespace avsm::passes {

namespace {

using HairPush = shared::HairPush;  // shaders/shared/passes/camera/hair/hair.h

// Central differences inside a strand, one-sided at its ends.
void add_tangents(const scene::HairGroom& groom, std::vector<glm::vec4>& tangents) {
  for (size_t s = 0; s < groom.strand_count(); ++s) {
    const uint32_t first = groom.strand_offsets[s], last = groom.strand_offsets[s + 1] - 1;
    for (uint32_t p = first; p <= last; ++p) {
      const glm::vec3 d = groom.points[std::min(p + 1, last)] - groom.points[p > first ? p - 1 : p];
      const float length = glm::length(d);
      tangents.emplace_back(length > 0.0f ? d / length : glm::vec3(0.0f, 1.0f, 0.0f), 0.0f);
    }
  }
}

}  // namespace

HairPass::HairPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) : ctx_(ctx) {
  gpu::GraphicsPipelineDesc desc;
  desc.name = "hair";
  desc.vertex = shaders.load("shaders/passes/camera/hair/hair.vert");
  desc.fragment = shaders.load("shaders/passes/camera/hair/hair.frag");
  desc.color_formats = {OpaquePass::kColorFormat};
  desc.depth_format = OpaquePass::kDepthFormat;
  desc.depth_test = true;
  desc.depth_write = false;
  desc.blend = gpu::BlendMode::PremultipliedAlpha;
  lit_per_vertex_ = gpu::Pipeline::graphics(ctx, desc);
  desc.name = "hair reference";
  desc.fragment = shaders.load("shaders/passes/camera/hair/hair_reference.frag");
  lit_per_fragment_ = gpu::Pipeline::graphics(ctx, desc);
}

void HairPass::set_scene(const scene::Scene& scene) {
  std::vector<glm::vec4> points, tangents;
  std::vector<glm::uvec2> segments;  // (first point, strand)
  std::vector<shared::Strand> strands;
  for (const scene::HairGroom& groom : scene.hair) {
    uint32_t point_base = uint32_t(points.size());
    for (const glm::vec3& p : groom.points) points.emplace_back(p, 1.0f);
    add_tangents(groom, tangents);
    for (size_t s = 0; s < groom.strand_count(); ++s) {
      uint32_t strand = uint32_t(strands.size());
      strands.push_back({glm::vec4(groom.strand_color[s], groom.strand_opacity[s]), groom.strand_width[s], {}});
      for (uint32_t p = groom.strand_offsets[s]; p + 1 < groom.strand_offsets[s + 1]; ++p)
        segments.emplace_back(point_base + p, strand);
    }
  }
  segment_count_ = uint32_t(segments.size());
  point_count_ = uint32_t(points.size());
  tangents_ = gpu::create_buffer_from(ctx_, std::move(tangents), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "hair tangents");
  points_ = gpu::create_buffer_from(ctx_, std::move(points), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "hair points");
  segments_ = gpu::create_buffer_from(ctx_, std::move(segments), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "hair segments");
  strands_ = gpu::create_buffer_from(ctx_, std::move(strands), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "hair strands");
}

rg::TextureHandle HairPass::add_to_graph(rg::Graph& graph, rg::TextureHandle color, rg::TextureHandle depth,
                                         rg::BufferHandle vertex_lights, bool light_per_fragment,
                                         FrameInputs& frame) {
  const View& view = frame.view;
  const gpu::Buffer& lights = *frame.lights;
  const uint32_t light_count = frame.light_count;
  const ShadowInputs shadows = frame.shadows;
  if (segment_count_ == 0) return color;
  struct Targets {
    rg::TextureHandle color, depth;
    rg::BufferHandle vertex_lights, page_requests;
  };
  const Targets& targets = graph.add_pass<Targets>("hair", rg::QueueType::Graphics,
      [&](rg::PassBuilder& b, Targets& d) {
        d.color = b.read_write(color, rg::Usage::ColorAttachment);
        d.depth = b.read(depth, rg::Usage::DepthAttachmentRead);
        d.vertex_lights = b.read(vertex_lights, rg::Usage::StorageRead);
        if (light_per_fragment) {
          shadows.declare_reads(b);
          d.page_requests = frame.ask_for_pages(b);
        }
      },
      [this, view, &lights, light_count, shadows, light_per_fragment](const Targets& d, rg::PassContext& c) {
        VkCommandBuffer cmd = c.cmd();
        gpu::ColorTarget color_target{c.view(d.color), c.layout(d.color), {}, /*load=*/true};
        gpu::DepthTarget depth_target{c.view(d.depth), c.layout(d.depth), 1.0f, /*store=*/false, /*read_only=*/true};
        gpu::begin_rendering(cmd, {view.width, view.height}, {&color_target, 1}, &depth_target, /*flip_y=*/true);
        const gpu::Pipeline& pipeline = light_per_fragment ? lit_per_fragment_ : lit_per_vertex_;
        pipeline.bind(cmd);
        gpu::Bindings bindings(ctx_, pipeline);
        bindings.buffer("Points", points_)
            .buffer("Segments", segments_)
            .buffer("Strands", strands_)
            .buffer("VertexLights", c.buffer(d.vertex_lights));
        if (light_per_fragment) {
          bindings.buffer("Lights", lights);
          shadows.bind(bindings, c);
          shadows.bind_page_requests(bindings, c, d.page_requests);
        }
        bindings.push(cmd);
        pipeline.push_constants(cmd, HairPush{view.view_projection, glm::vec4(view.camera_position, 1.0f),
                                               glm::vec2(view.width, view.height), light_count,
                                               0.0f});
        vkCmdDraw(cmd, segment_count_ * 6, 1, 0, 0);
        vkCmdEndRendering(cmd);
      });
  return targets.color;
}

}  // namespace avsm::passes
