#pragma once
// Shadow quality against the exact reference: per camera pixel and per light, the
// absolute difference between the technique's transmittance and the exact one
// (the light's capture lists, ShadowOptions::keep_reference) at the receivers the
// pixel sees: the opaque surface in the depth buffer and points inside the smoke.
// Hair is measured by passes/camera/quality/shadow_quality_hair_pass.h. The per-pixel errors land in a
// host-readable buffer; engine/capture/quality.h turns them into figures and
// images (avsm-capture --compare-to uncompressed).
// Shader: shaders/passes/camera/quality/shadow_quality.comp (which receivers count, exactly).
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/executor.h>

#include <cstdint>
#include <vector>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/shader_compiler.h"
#include "passes/shadows/shadow_maps.h"
#include "passes/camera/quality/per_pixel_results.h"
#include "passes/frame/view.h"
#include "passes/camera/volumes/volume_pass.h"
#include "shared/passes/camera/quality/shadow_quality.h"

namespace avsm::passes {

struct FrameInputs;  // passes/frame/frame_inputs.h

using shared::PixelShadowError;  // shaders/shared/passes/camera/quality/shadow_quality.h

class ShadowQualityPass {
 public:
  // Smoke receivers per volume along a pixel ray: evenly spaced over the ray's
  // stretch inside the volume's support (those with density > 0 count).
  static constexpr uint32_t kSmokeSamplesPerVolume = 4;

  ShadowQualityPass(gpu::Context& ctx, const gpu::ShaderLibrary& shaders);

  // Sizes the result buffer for `light_count` lights on a width x height image.
  void set_size(uint32_t width, uint32_t height, uint32_t light_count);
  // A result buffer per frame in flight (passes/frame/frames_in_flight.h; 1 by default).
  void set_frames_in_flight(uint32_t count) { results_.set_frames(ctx_, count); }

  // Adds "shadow quality" after the camera passes: reads `depth` (the opaque depth
  // buffer, D32_SFLOAT, width x height), the frame's volumes and shadows. The shadows
  // should come from ShadowMaps with keep_reference on (without it the reference is
  // the technique itself and every error is 0).
  void add_to_graph(rg::Graph& graph, rg::TextureHandle depth, const FrameInputs& frame);

  // After the frame recorded into `slot` completed: [light * width * height + y * width + x],
  // row 0 at the top.
  std::vector<PixelShadowError> results(uint32_t slot = 0) const { return results_.read(slot); }
  uint32_t width() const { return results_.width(); }
  uint32_t height() const { return results_.height(); }
  uint32_t light_count() const { return results_.light_count(); }

 private:
  gpu::Context& ctx_;
  gpu::Pipeline pipeline_;
  gpu::Sampler depth_sampler_;
  PerPixelResults<PixelShadowError> results_;
};

}  // namespace avsm::passes
