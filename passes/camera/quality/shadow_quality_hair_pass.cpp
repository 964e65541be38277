#include "passes/camera/quality/shadow_quality_hair_pass.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <cstring>

#include "passes/frame/frame_inputs.h"
#include "shared/passes/camera/quality/shadow_quality_hair.h"

namespace avsm::passes {
namespace {

using Push = shared::ShadowQualityHairPush;  // shaders/shared/passes/camera/quality/shadow_quality_hair.h

}  // namespace

ShadowQualityHairPass::ShadowQualityHairPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders)
    : ctx_(ctx),
      pipeline_(gpu::Pipeline::compute(ctx, shaders.load("shaders/passes/camera/quality/shadow_quality_hair.comp"),
                                       "shadow quality hair")),
      depth_sampler_(ctx, gpu::texel_sampler_desc("quality hair depth")) {}

void ShadowQualityHairPass::set_hair(const HairPass& hair, uint32_t light_count) {
  const uint32_t vertices = hair.segment_count() ? uint32_t(hair.points().size() / sizeof(glm::vec4)) : 0;
  points_ = &hair.points();
  stride_ = std::max(1u, (vertices + kMaxReceivers - 1) / kMaxReceivers);
  receiver_count_ = vertices / stride_;
  light_count_ = light_count;
  results_.create(ctx_, {std::max<uint64_t>(uint64_t(receiver_count_) * light_count, 1) * sizeof(float),
                         VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryLocation::HostReadback,
                         "shadow quality hair errors"});
}

void ShadowQualityHairPass::add_to_graph(rg::Graph& graph, rg::TextureHandle depth, const FrameInputs& frame) {
  const View& view = frame.view;
  const ShadowInputs& shadows = frame.shadows;
  if (receiver_count_ == 0 || light_count_ == 0) return;
  rg::BufferHandle results = rg::vulkan::import(graph, "shadow quality hair errors", results_[shadows.frame_slot],
                                                rg::ImportState::none(),
                                                rg::ImportState::of(rg::Usage::HostRead));
  struct Data {
    rg::TextureHandle depth;
    rg::BufferHandle results;
  };
  graph.add_pass<Data>("shadow quality hair", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Data& data) {
        data.depth = b.read(depth, rg::Usage::Sampled);
        data.results = b.write(results, rg::Usage::StorageWrite);
        shadows.declare_reads(b);
      },
      [this, view, shadows](const Data& data, rg::PassContext& c) {
        pipeline_.bind(c.cmd());
        gpu::Bindings bindings(ctx_, pipeline_);
        bindings.buffer("Points", *points_)
            .image("depth_texture", c.view(data.depth), c.layout(data.depth), depth_sampler_.handle())
            .buffer("Results", c.buffer(data.results));
        shadows.bind(bindings, c);
        bindings.push(c.cmd());
        pipeline_.push_constants(c.cmd(), Push{view.view_projection, {view.width, view.height}, receiver_count_,
                                               stride_, light_count_});
        pipeline_.dispatch_threads(c.cmd(), receiver_count_);
      });
}

std::vector<float> ShadowQualityHairPass::results(uint32_t slot) const {
  std::vector<float> out(size_t(receiver_count_) * light_count_);
  if (!out.empty()) std::memcpy(out.data(), results_[slot].mapped(), out.size() * sizeof(float));
  return out;
}

}  // namespace avsm::passes
