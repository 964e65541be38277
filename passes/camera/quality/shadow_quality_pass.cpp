#include "passes/camera/quality/shadow_quality_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <stdexcept>
#include <string>

#include "gpu/context.h"
#include "passes/frame/frame_inputs.h"
#include "shared/passes/camera/quality/shadow_quality.h"

namespace avsm::passes {
namespace {

using Push = shared::ShadowQualityPush;  // shaders/shared/passes/camera/quality/shadow_quality.h

}  // namespace

ShadowQualityPass::ShadowQualityPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/quality/shadow_quality.comp"), "shadow quality")),
      depth_sampler_(ctx, gpu::texel_sampler_desc("quality depth")) {}

void ShadowQualityPass::set_size(uint32_t width, uint32_t height, uint32_t light_count) {
  results_.set_size(ctx_, width, height, light_count, "shadow quality errors");
}

void ShadowQualityPass::add_to_graph(rg::Graph& graph, rg::TextureHandle depth, const FrameInputs& frame) {
  const View& view = frame.view;
  const gpu::Buffer& lights = *frame.lights;
  const uint32_t light_count = frame.light_count;
  const VolumePass& volumes = *frame.volumes;
  const ShadowInputs& shadows = frame.shadows;
  const uint32_t width = results_.width(), height = results_.height();
  if (results_.light_count() == 0 || width == 0 || height == 0) return;
  if (light_count != results_.light_count())
    throw std::invalid_argument("ShadowQualityPass: sized for " + std::to_string(results_.light_count()) +
                                " lights, got " + std::to_string(light_count));
  const rg::TextureDesc& d = graph.resources().at(depth.index).texture;
  if (d.width != width || d.height != height || d.format != VolumePass::kDepthFormat)
    throw std::invalid_argument("ShadowQualityPass: depth must be D32_SFLOAT " + std::to_string(width) + "x" +
                                std::to_string(height));
  rg::BufferHandle results = rg::vulkan::import(graph, "shadow quality errors", results_[shadows.frame_slot],
                                                rg::ImportState::none(),
                                                rg::ImportState::of(rg::Usage::HostRead));
  struct Data {
    rg::TextureHandle depth;
    rg::BufferHandle results;
  };
  const VolumeCasters volume_data = volumes.casters();
  graph.add_pass<Data>("shadow quality", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& data) {
        data.depth = b.read(depth, rg::Usage::Sampled);
        data.results = b.write(results, rg::Usage::StorageWrite);
        shadows.declare_reads(b);
      },
      [this, view, &lights, light_count, shadows, volume_data, width, height](const Data& data, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline_);
        bindings.image("depth_texture", c.view(data.depth), c.layout(data.depth), depth_sampler_.handle())
            .buffer("Errors", c.buffer(data.results))
            .buffer("Lights", lights);
        bind_volumes(bindings, volume_data, /*with_atlas=*/false);
        shadows.bind(bindings, c);
        bindings.push(c.cmd());
        const Push push{view.inverse_view_projection, view.camera_position, volume_data.volume_count, {width, height},
                        light_count, kSmokeSamplesPerVolume};
        pipeline_.push_constants(c.cmd(), push);
        pipeline_.dispatch_threads(c.cmd(), width, height);
      });
}

}  // namespace avsm::passes
