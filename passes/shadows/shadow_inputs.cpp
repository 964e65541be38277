#include "passes/shadows/shadow_inputs.h"

#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>

#include "gpu/pipeline.h"
#include "gpu/transfer.h"

namespace avsm::passes {

void ShadowInputs::declare_reads(rg::PassBuilder& builder) const {
  if (records.valid()) builder.read(records, rg::Usage::StorageRead);
  for (rg::BufferHandle map : maps) builder.read(map, rg::Usage::StorageRead);
  for (rg::BufferHandle list : lists) builder.read(list, rg::Usage::StorageRead);
  if (fog_grid.valid()) builder.read(fog_grid, rg::Usage::StorageRead);
}

void ShadowInputs::bind_fog(gpu::Bindings& bindings, const rg::PassContext& context) const {
  bindings.buffer("Fog", fog_parameters).buffer("FogIntegrated", fog_grid.valid() ? context.buffer(fog_grid) : fog_parameters);
}

void ShadowInputs::bind(gpu::Bindings& bindings, const rg::PassContext& context) const {
  auto or_unused = [&](const gpu::BufferRange& range) { return range.buffer ? range : gpu::BufferRange(unused_buffer); };
  bindings.buffer("ShadowParameters", records.valid() ? context.buffer(records) : gpu::BufferRange(parameters))
      .buffer("ShadowMapAtlas", or_unused(atlas))
      .buffer("ShadowListHeads", or_unused(list_heads))
      .buffer("ShadowListNodes", or_unused(list_nodes));
}

rg::BufferHandle ShadowInputs::declare_page_requests(rg::PassBuilder& builder) const {
  return page_requests.valid() ? builder.write(page_requests, rg::Usage::StorageReadWrite) : rg::BufferHandle{};
}

void ShadowInputs::bind_page_requests(gpu::Bindings& bindings, const rg::PassContext& context,
                                      rg::BufferHandle requests) const {
  // Without paged maps no record asks (page_requests_offset is kNoPageRequests): any
  // buffer will do.
  bindings.buffer("ShadowPageRequests", requests.valid() ? context.buffer(requests) : gpu::BufferRange(unused_buffer));
}

UnshadowedInputs::UnshadowedInputs(gpu::Context& ctx) : ctx_(ctx) { reserve(64); }

void UnshadowedInputs::reserve(uint32_t lights) {
  const uint64_t count = std::max(lights, 64u);
  if (parameters_ && parameters_.size() >= count * sizeof(GpuShadow)) return;
  parameters_ = gpu::create_buffer_from(ctx_, std::vector<GpuShadow>(count, GpuShadow{}),
                                        VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "unshadowed parameters");
}

ShadowInputs UnshadowedInputs::inputs() const {
  ShadowInputs inputs;
  inputs.parameters = parameters_.handle();
  inputs.unused_buffer = parameters_.handle();
  return inputs;
}

}  // namespace avsm::passes
