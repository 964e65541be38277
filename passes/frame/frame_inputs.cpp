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

rg::BufferHandle FrameInputs::ask_for_pages(rg::PassBuilder& builder) {
  shadows.page_requests = shadows.declare_page_requests(builder);
  return shadows.page_requests;
}

rg::BufferHandle FrameInputs::declare_volume_access(rg::PassBuilder& builder) {
  if (cache) cache->declare_reads(builder);
  shadows.declare_reads(builder);
  return map_lookups() ? ask_for_pages(builder) : rg::BufferHandle{};
}

void FrameInputs::bind_volumes(gpu::Bindings& bindings, const rg::PassContext& context,
                               rg::BufferHandle page_requests) const {
  passes::bind_volumes(bindings, volumes->casters(), /*with_atlas=*/true);
  cache.value().bind(bindings, context);
  if (!map_lookups()) return;
  bindings.buffer("Lights", *lights);
  shadows.bind(bindings, context);
  shadows.bind_page_requests(bindings, context, page_requests);
}

}  // namespace avsm::passes
