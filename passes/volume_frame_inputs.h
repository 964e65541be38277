#pragma once
// What the camera-side volume passes read in one frame, gathered once by the renderer:
// the volumes, this frame's lighting cache (fast path only), the shading settings, and
// the lights and shadow maps. The lighting cache pass fills in `cache`; the march,
// the composite and the hair lighting read the rest. Passes keep a copy until they
// record: the graph handles are values, and the volume pass and light buffer outlive
// the frame.
#include <rendergraph/graph.h>

#include <cstdint>
#include <optional>

#include "gpu/resources.h"
#include "passes/shadow_inputs.h"
#include "passes/volume_pass.h"

namespace avsm::passes {

// One frame's lighting cache (passes/volume_lighting_cache_pass.h): the image, the
// per-volume layouts, and the sampler its readers filter it with.
struct VolumeLightingCache {
  rg::TextureHandle image;
  rg::BufferHandle layouts;
  VkSampler sampler = VK_NULL_HANDLE;
  void declare_reads(rg::PassBuilder& builder) const;
  void bind(gpu::Bindings& bindings, const rg::PassContext& context) const;
};

struct VolumeFrameInputs {
  const VolumePass* volumes = nullptr;
  VolumeShading shading;
  const gpu::Buffer* lights = nullptr;  // one GpuLight per light (passes/lights.h)
  uint32_t light_count = 0;
  ShadowInputs shadows;
  std::optional<VolumeLightingCache> cache;  // set by VolumeLightingCachePass in the fast path

  // The camera sees the smoke (the hair sees it in front of itself).
  bool smoke_visible() const { return shading.mode != VolumeShading::Mode::hidden; }
  // Whether the fast passes need their variant with shadow-map lookups (a volume's cache is off).
  bool map_lookups() const { return volumes->needs_map_lookups(); }
  // The cache (when there is one) and the shadow maps.
  void declare_reads(rg::PassBuilder& builder) const;
  // For the fast march and composite: the volumes with their atlas, the cache and, with
  // map lookups, the lights and the shadow maps. Needs the cache.
  void bind(gpu::Bindings& bindings, const rg::PassContext& context) const;
};

}  // namespace avsm::passes
