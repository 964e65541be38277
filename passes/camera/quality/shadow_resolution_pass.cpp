#include "passes/camera/quality/shadow_resolution_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "passes/camera/volumes/volume_pass.h"
#include "passes/frame/frame_inputs.h"

namespace avsm::passes {
namespace {

using Push = shared::ShadowResolutionPush;  // shaders/shared/passes/camera/quality/shadow_resolution.h

}  // namespace

ShadowResolutionPass::ShadowResolutionPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/quality/shadow_resolution.comp"),
                                       "shadow resolution")),
      depth_sampler_(ctx, gpu::texel_sampler_desc("resolution depth")) {}

void ShadowResolutionPass::set_size(uint32_t width, uint32_t height, uint32_t light_count) {
  results_.set_size(ctx_, width, height, light_count, "shadow resolution figures");
}

rg::BufferHandle ShadowResolutionPass::add_to_graph(rg::Graph& graph, rg::TextureHandle depth,
                                                    const FrameInputs& frame) {
  const uint32_t width = results_.width(), height = results_.height();
  if (frame.light_count != results_.light_count())
    throw std::invalid_argument("ShadowResolutionPass: sized for " + std::to_string(results_.light_count()) +
                                " lights, got " + std::to_string(frame.light_count));
  const rg::TextureDesc& d = graph.resources().at(depth.index).texture;
  if (d.width != width || d.height != height || d.format != VolumePass::kDepthFormat)
    throw std::invalid_argument("ShadowResolutionPass: depth must be D32_SFLOAT " + std::to_string(width) + "x" +
                                std::to_string(height));
  const ShadowInputs& shadows = frame.shadows;
  rg::BufferHandle results = rg::vulkan::import(graph, "shadow resolution", results_[shadows.frame_slot],
                                                rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
  struct Data {
    rg::TextureHandle depth;
    rg::BufferHandle results;
  };
  const gpu::Buffer& lights = *frame.lights;
  const Push push{frame.view.inverse_view_projection, frame.view.camera_position, frame.light_count, {width, height}};
  return graph.add_pass<Data>("shadow resolution", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& data) {
        data.depth = b.read(depth, rg::Usage::Sampled);
        data.results = b.write(results, rg::Usage::StorageWrite);
        shadows.declare_reads(b);
      },
      [this, &lights, shadows, push](const Data& data, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline_);
        bindings.image("depth_texture", c.view(data.depth), c.layout(data.depth), depth_sampler_.handle())
            .buffer("Results", c.buffer(data.results))
            .buffer("Lights", lights);
        shadows.bind(bindings, c);
        bindings.push(c.cmd());
        pipeline_.push_constants(c.cmd(), push);
        pipeline_.dispatch_threads(c.cmd(), push.image_size.x, push.image_size.y);
      }).results;
}

}  // namespace avsm::passes
