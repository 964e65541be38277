#pragma once
// What the camera passes read in one frame, published once by the renderer
// (renderer::SceneRenderer::build_frame): the view, the lights and their shadow maps,
// the volumes with their shading settings and this frame's lighting cache (fast path
// only; the lighting cache pass fills it in). Each pass takes the whole FrameInputs and
// reads what it needs. Passes keep a copy until they record: the graph handles are
// values, and the volume pass and light buffer outlive the frame.
#include <rendergraph/graph.h>

#include <cstdint>
#include <optional>
#include <vector>

#include "gpu/resources.h"
#include "passes/shadows/light_view.h"
#include "passes/shadows/shadow_inputs.h"
#include "passes/frame/view.h"
#include "passes/camera/fog/fog_media.h"
#include "passes/camera/volumes/volume_pass.h"

namespace avsm::passes {

// One frame's lighting cache (passes/camera/volumes/volume_lighting_cache_pass.h): the image, the
// per-volume layouts, and the sampler its readers filter it with.
struct VolumeLightingCache {
  rg::TextureHandle image;
  rg::BufferHandle layouts;
  VkSampler sampler = VK_NULL_HANDLE;
  void declare_reads(rg::PassBuilder& builder) const;
  void bind(gpu::Bindings& bindings, const rg::PassContext& context) const;
};

struct FrameInputs {
  View view;
  const VolumePass* volumes = nullptr;
  VolumeShading shading;
  const gpu::Buffer* lights = nullptr;  // one GpuLight per light (passes/frame/lights.h)
  uint32_t light_count = 0;
  // Map lookups a point's transmittance takes over every light: one per light, an area
  // light's virtual lights each (what per-pixel marches split their steps by: lavapipe's
  // loop budget).
  uint32_t lookups_per_point = 1;
  ShadowInputs shadows;
  const std::vector<LightView>* light_views = nullptr;  // the shadowed lights' maps
  std::optional<VolumeLightingCache> cache;  // set by VolumeLightingCachePass in the fast path
  FogInputs fog;  // the fog's buffer always; its integrated grid when the frame has fog

  // The camera sees the smoke (the hair sees it in front of itself).
  bool smoke_visible() const { return shading.mode != VolumeShading::Mode::hidden; }
  // Whether the fast passes need their variant with shadow-map lookups (a volume's cache is off).
  bool map_lookups() const { return volumes->needs_map_lookups(); }
  // For a pass whose receivers ask paged maps for pages (AVSM_SHADOW_PAGE_REQUESTS_BINDING),
  // in its setup: declares its writes to the request bits, and makes the new version the
  // one the next such pass writes. Bind the result with shadows.bind_page_requests().
  rg::BufferHandle ask_for_pages(rg::PassBuilder& builder);
  // For the fast volume passes: the cache (when there is one) and the shadow maps; with
  // map lookups, their receivers ask for pages (returned, else invalid).
  rg::BufferHandle declare_volume_access(rg::PassBuilder& builder);
  // For the fast march and composite: the volumes with their atlas, the cache and, with
  // map lookups, the lights, the shadow maps and the page requests. Needs the cache.
  void bind_volumes(gpu::Bindings& bindings, const rg::PassContext& context, rg::BufferHandle page_requests) const;
};

}  // namespace avsm::passes
