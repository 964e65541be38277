#include "passes/volume_frame_inputs.h"

#include <rendergraph/vulkan/pass_context.h>

#include "gpu/pipeline.h"

namespace avsm::passes {

void VolumeLightingCache::declare_reads(rg::PassBuilder& builder) const {
  builder.read(image, rg::Usage::Sampled);
  builder.read(layouts, rg::Usage::StorageRead);
}

void VolumeLightingCache::bind(gpu::Bindings& bindings, uint32_t first_binding, const rg::PassContext& context) const {
  bindings.buffer(first_binding, context.buffer(layouts))
      .image(first_binding + 1, context.view(image), context.layout(image), sampler);
}

void VolumeFrameInputs::declare_reads(rg::PassBuilder& builder) const {
  if (cache) cache->declare_reads(builder);
  shadows.declare_reads(builder);
}

void VolumeFrameInputs::bind(gpu::Bindings& bindings, uint32_t first, const rg::PassContext& context) const {
  bind_volumes(bindings, volumes->casters(), first, /*with_atlas=*/true);
  cache.value().bind(bindings, first + 5, context);
  if (!map_lookups()) return;
  bindings.buffer(first + 7, lights->handle());
  shadows.bind(bindings, first + 8, context);
}

}  // namespace avsm::passes
