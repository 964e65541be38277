#pragma once
// The homogeneous fog (scene/fog.h) as the camera passes see it in one frame:
// FogMedia writes each frame's grid header and media (shared/fog.h) into that frame
// slot's buffer; FogInputs (in FrameInputs) is what the composites bind. The fog's
// passes, in order: FogScatteringPass (the froxels), FogIntegrationPass (front to back)
// and FogApplyPass (onto the opaque colour); the smoke and hair composites read the
// integrated grid at their own distances.
#include <rendergraph/graph.h>
#include <rendergraph/vulkan/pass_context.h>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "passes/frame/frames_in_flight.h"
#include "passes/frame/view.h"
#include "scene/bounds.h"
#include "scene/fog.h"
#include "shared/fog.h"

namespace avsm::passes {

// The froxel grid's extent in one frame: columns x rows x slices.
struct FogGridSize {
  uint32_t columns = 0, rows = 0, slices = 0;
};

// The header and media a frame's fog passes read: the global fog as box 0, holding all
// space, then the boxes. The grid reaches from the camera to grid.distance, or else to
// the far side of `scene_bounds` (what the background sees through).
struct GpuFog {
  shared::GpuFogGrid grid{};
  std::vector<shared::GpuFogBox> media;
};
GpuFog gpu_fog(const scene::Fog& fog, const View& view, const scene::Bounds& scene_bounds);
FogGridSize fog_grid_size(const shared::GpuFogGrid& grid);

// What the passes that composite fog bind (AVSM_FOG_BINDING, AVSM_FOG_INTEGRATED_BINDING
// in common/fog.glsl): the frame's Fog buffer and its integrated grid (a buffer of the
// frame slot's, which outlives the frame's passes: a host reads it after its pass list).
// A frame without fog binds the Fog buffer in the grid's place, unread (its header says
// enabled = 0).
struct FogInputs {
  const gpu::Buffer* parameters = nullptr;
  const gpu::Buffer* integrated_buffer = nullptr;  // the slot's grid
  FogGridSize size;               // this frame's grid
  rg::BufferHandle integrated;    // invalid: no fog this frame (set by FogIntegrationPass)

  bool enabled() const { return integrated.valid(); }
  void declare_reads(rg::PassBuilder& builder) const;
  void bind(gpu::Bindings& bindings, const rg::PassContext& context) const;
};

class FogMedia {
 public:
  explicit FogMedia(gpu::Context& ctx);

  // Another fog (or the same over other bounds) for the next frame written; waits for the
  // device to idle only when it has more boxes than the slots' buffers hold.
  void set_fog(const scene::Fog& fog, const scene::Bounds& scene_bounds);
  const scene::Fog& fog() const { return fog_; }
  // Hosts and the viewer switch the fog off without losing its settings.
  void set_enabled(bool enabled) { enabled_ = enabled; }
  bool enabled() const { return enabled_ && fog_.enabled(); }
  void set_frames_in_flight(uint32_t count);

  // Writes slot's buffer for `view` (the slot's previous frame has completed) and returns
  // the inputs of a frame without fog yet: FogIntegrationPass sets `integrated`. A grid
  // larger than the slots' buffers hold (a larger view, finer froxels) makes them again,
  // after waiting for the device to idle.
  FogInputs write(uint32_t slot, const View& view);
  // The grid that write() describes for `view`.
  GpuFog describe(const View& view) const;

 private:
  gpu::Context& ctx_;
  scene::Fog fog_;
  scene::Bounds scene_bounds_;
  bool enabled_ = true;
  FrameBuffers buffers_;     // the grid header and media, per slot
  uint64_t media_bytes_ = 0;
  FrameBuffers integrated_;  // the integrated grid, per slot
  uint64_t integrated_bytes_ = 0;
};

}  // namespace avsm::passes
