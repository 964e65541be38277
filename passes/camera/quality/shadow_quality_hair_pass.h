#pragma once
// Shadow quality at the hair: per strand vertex the camera sees (inside the view,
// not behind the opaque depth; every `stride`-th vertex, at most kMaxReceivers) and
// per light, |T - T_ref| against the exact reference (ShadowOptions::keep_reference),
// looked up as the hair pass shades. Results land in a host-readable buffer for
// engine/capture/quality.h. Shader: shaders/passes/camera/quality/shadow_quality_hair.comp.
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <cstdint>
#include <vector>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/camera/hair/hair_pass.h"
#include "passes/shadows/shadow_maps.h"
#include "passes/frame/view.h"

namespace avsm::passes {

struct FrameInputs;  // passes/frame/frame_inputs.h

class ShadowQualityHairPass {
 public:
  static constexpr uint32_t kMaxReceivers = 1u << 16;

  ShadowQualityHairPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // Sizes the results for `hair`'s vertices and `light_count` lights.
  void set_hair(const HairPass& hair, uint32_t light_count);
  // A result buffer per frame in flight (passes/frame/frames_in_flight.h; 1 by default).
  void set_frames_in_flight(uint32_t count) { results_.set_frames(ctx_, count); }
  // Adds "shadow quality hair" reading `depth` (the opaque depth buffer) and the shadows.
  void add_to_graph(rg::Graph& graph, rg::TextureHandle depth, const FrameInputs& frame);
  // After the frame recorded into `slot`: [light * receiver_count() + receiver], -1 where
  // not a receiver.
  std::vector<float> results(uint32_t slot = 0) const;
  uint32_t receiver_count() const { return receiver_count_; }

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Sampler depth_sampler_;
  FrameBuffers results_;
  const gpu::Buffer* points_ = nullptr;
  uint32_t receiver_count_ = 0, stride_ = 1, light_count_ = 0;
};

}  // namespace avsm::passes
