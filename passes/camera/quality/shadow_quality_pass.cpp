#include "passes/camera/quality/shadow_quality_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cstring>
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
      depth_sampler_(ctx, {VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST, VK_SAMPLER_ADDRESS_MODE_CLAMP_TO_EDGE,
                           false, VK_COMPARE_OP_LESS_OR_EQUAL, VK_BORDER_COLOR_FLOAT_OPAQUE_WHITE, "quality depth"}) {}

void ShadowQualityPass::set_size(uint32_t width, uint32_t height, uint32_t light_count) {
  const uint64_t bytes = uint64_t(width) * height * std::max(light_count, 1u) * sizeof(PixelShadowError);
  if (bytes > ctx_.info().max_storage_buffer_range)
    throw std::invalid_argument("shadow quality: " + std::to_string(width) + "x" + std::to_string(height) +
                                " pixels for " + std::to_string(light_count) + " lights need " +
                                std::to_string(bytes >> 20) + " MiB of per-pixel errors, more than the device's " +
                                std::to_string(ctx_.info().max_storage_buffer_range >> 20) +
                                " MiB storage buffer range; capture smaller images (--width/--height) or fewer lights");
  width_ = width;
  height_ = height;
  light_count_ = light_count;
  const uint64_t entries = std::max<uint64_t>(uint64_t(width) * height * light_count, 1);
  results_.create(ctx_, {entries * sizeof(PixelShadowError), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                         gpu::MemoryLocation::HostReadback, "shadow quality errors"});
}

void ShadowQualityPass::add_to_graph(rg::Graph& graph, rg::TextureHandle depth, const FrameInputs& frame) {
  const View& view = frame.view;
  const gpu::Buffer& lights = *frame.lights;
  const uint32_t light_count = frame.light_count;
  const VolumePass& volumes = *frame.volumes;
  const ShadowInputs& shadows = frame.shadows;
  if (light_count_ == 0 || width_ == 0 || height_ == 0) return;
  if (light_count != light_count_)
    throw std::invalid_argument("ShadowQualityPass: sized for " + std::to_string(light_count_) + " lights, got " +
                                std::to_string(light_count));
  const rg::TextureDesc& d = graph.resources().at(depth.index).texture;
  if (d.width != width_ || d.height != height_ || d.format != VolumePass::kDepthFormat)
    throw std::invalid_argument("ShadowQualityPass: depth must be D32_SFLOAT " + std::to_string(width_) + "x" +
                                std::to_string(height_));
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
      [this, view, &lights, light_count, shadows, volume_data](const Data& data, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline_);
        bindings.image("depth_texture", c.view(data.depth), c.layout(data.depth), depth_sampler_.handle())
            .buffer("Errors", c.buffer(data.results))
            .buffer("Lights", lights);
        bind_volumes(bindings, volume_data, /*with_atlas=*/false);
        shadows.bind(bindings, c);
        bindings.push(c.cmd());
        const Push push{view.inverse_view_projection, view.camera_position, volume_data.volume_count, {width_, height_},
                        light_count, kSmokeSamplesPerVolume};
        pipeline_.push_constants(c.cmd(), push);
        pipeline_.dispatch_threads(c.cmd(), width_, height_);
      });
}

std::vector<PixelShadowError> ShadowQualityPass::results(uint32_t slot) const {
  const size_t count = size_t(width_) * height_ * light_count_;
  std::vector<PixelShadowError> out(count);
  if (count) std::memcpy(out.data(), results_[slot].mapped(), count * sizeof(PixelShadowError));
  return out;
}

}  // namespace avsm::passes
