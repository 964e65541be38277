#pragma once
// How well the shadow maps' resolution matches the camera's: per camera pixel and per
// light, at the opaque surface in the depth buffer where the light reaches it, the
// level the surface lookup reads and the widest its texels are on screen, in pixels.
// The results land in a host-readable buffer; engine/capture/resolution.h turns them
// into figures and pictures (avsm-capture --measure-resolution), and the viewer colours
// receivers by the level they read (shadow_level_overlay_pass.h).
// Shader: shaders/passes/camera/quality/shadow_resolution.comp (which pixels count, exactly).
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <cstdint>
#include <vector>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/camera/quality/per_pixel_results.h"
#include "shared/passes/camera/quality/shadow_resolution.h"

namespace avsm::passes {

struct FrameInputs;  // passes/frame/frame_inputs.h

using shared::PixelShadowResolution;  // shaders/shared/passes/camera/quality/shadow_resolution.h

class ShadowResolutionPass {
 public:
  ShadowResolutionPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // Sizes the result buffer for `light_count` lights on a width x height image.
  void set_size(uint32_t width, uint32_t height, uint32_t light_count);
  void set_frames_in_flight(uint32_t count) { results_.set_frames(ctx_, count); }

  // Adds "shadow resolution" after the opaque pass: reads `depth` (D32_SFLOAT, width x
  // height) and the frame's shadows. Returns the results, for a pass that shows them.
  rg::BufferHandle add_to_graph(rg::Graph& graph, rg::TextureHandle depth, const FrameInputs& frame);

  // After the frame recorded into `slot` completed: [light * width * height + y * width + x],
  // row 0 at the top.
  std::vector<PixelShadowResolution> results(uint32_t slot = 0) const { return results_.read(slot); }

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Sampler depth_sampler_;
  PerPixelResults<PixelShadowResolution> results_;
};

}  // namespace avsm::passes
