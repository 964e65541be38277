#include "passes/frame/frame_inputs.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/pipeline.h"

namespace avsm::passes {

void VolumeLightingCache::declare_reads(rg::PassBuilder& builder) const {
  builder.read(image, rg::Usage::Sampled);
  builder.read(layouts, rg::Usage::StorageRead);
}

void VolumeLightingCache::bind(gpu::Bindings& bindings, const rg::PassContext& context) const {
  bindings.buffer("CacheLayouts", context.buffer(layouts))
      .image("lighting_cache", context.view(image), context.layout(image), sampler);
}

void FrameInputs::declare_volume_reads(rg::PassBuilder& builder) const {
  if (cache) cache->declare_reads(builder);
  shadows.declare_reads(builder);
}

void FrameInputs::bind_volumes(gpu::Bindings& bindings, const rg::PassContext& context) const {
  passes::bind_volumes(bindings, volumes->casters(), /*with_atlas=*/true);
  cache.value().bind(bindings, context);
  if (!map_lookups()) return;
  bindings.buffer("Lights", *lights);
  shadows.bind(bindings, context);
}

}  // namespace avsm::passes
