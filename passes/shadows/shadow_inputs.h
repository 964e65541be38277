#pragma once
// What a camera pass needs to look the shadow maps up (shaders/common/shadow_lookup.glsl):
// the per-light parameter block and the frame-graph handles of the maps. Produced by
// ShadowMaps::add_to_graph (passes/shadows/shadow_maps.h); kept apart so that a pass which only
// reads shadows does not include the whole shadow pipeline.
#include <rendergraph/graph.h>
#include <vulkan/vulkan.h>

#include <glm/glm.hpp>

#include <cstdint>
#include <vector>

#include "gpu/resources.h"
#include "shared/shadow.h"

namespace rg {
class PassContext;
}
namespace avsm::gpu {
class Bindings;
class Context;
}  // namespace avsm::gpu

namespace avsm::passes {

using shared::GpuShadow;  // shaders/shared/shadow.h
using shared::kNoReference;

// What a camera pass reads to look shadows up (shaders/common/shadow_lookup.glsl): the
// GpuShadow records and three buffers every record addresses by offset (the map atlas,
// and the looked-up capture lists' heads and nodes), bound whole. The graph orders the
// reads through each map's and list's own handle (a region of those buffers).
struct ShadowInputs {
  VkBuffer parameters = VK_NULL_HANDLE;  // the GpuShadow records
  // The same buffer as a graph resource when the frame writes it (ShadowMaps uploads the
  // records in a "shadow parameters" pass); invalid for static parameters.
  rg::BufferHandle records;
  // Every map this frame builds and every paged map's page pool (regions of `atlas`), and
  // the paged maps' page tables.
  std::vector<rg::BufferHandle> maps;
  std::vector<rg::BufferHandle> lists;  // the looked-up lists: regions of `list_heads`, `list_nodes`
  gpu::BufferRange atlas, list_heads, list_nodes;
  VkBuffer unused_buffer = VK_NULL_HANDLE;  // bound where there is no atlas or no lists
  // Paged maps' request bits (shaders/shared/pages.h), cleared by the frame: the passes
  // whose receivers ask for pages write them one after another (the opaque pass, hair
  // lighting, the volume lighting cache and march: FrameInputs::ask_for_pages); invalid
  // without paged maps.
  rg::BufferHandle page_requests;
  gpu::BufferRange page_request_bits;  // its bytes (this frame slot's), for a host's descriptor
  // The frame slot the graph records into (passes/frame/frames_in_flight.h): passes with a
  // buffer per frame in flight (readbacks) write this slot's.
  uint32_t frame_slot = 0;
  // A host's frame with the engine's fog (avsm::Shadows::set_fog, through
  // avsm::add_to_graph): the integrated grid the fog passes wrote (declared with the
  // reads), and the buffers its composite binds (bind_fog). Invalid, and unset, otherwise:
  // the engine's own camera passes take the fog from FrameInputs.
  rg::BufferHandle fog_grid;
  gpu::BufferRange fog_parameters, fog_grid_bytes;

  // Declares the reads in a camera pass's setup.
  void declare_reads(rg::PassBuilder& builder) const;
  // In the pass's execute step: the records, the atlas, the list heads and nodes, by
  // their shader names.
  void bind(gpu::Bindings& bindings, const rg::PassContext& context) const;
  // For a host's composite of the fog (shaders/common/fog.glsl): the "Fog" and
  // "FogIntegrated" buffers (the parameters twice when the frame has no fog; unread then).
  void bind_fog(gpu::Bindings& bindings, const rg::PassContext& context) const;
  // For a pass whose lookups ask for pages (AVSM_SHADOW_PAGE_REQUESTS_BINDING): declares
  // its writes to the request bits (returns the new version, invalid without paged maps)
  // and binds them, or a stand-in where the frame has no paged map.
  rg::BufferHandle declare_page_requests(rg::PassBuilder& builder) const;
  void bind_page_requests(gpu::Bindings& bindings, const rg::PassContext& context, rg::BufferHandle requests) const;
};

// Stand-ins bound where a light has no map or lists, and the parameter block of
// all-unshadowed lights: camera passes rendered without shadow maps use these.
class UnshadowedInputs {
 public:
  explicit UnshadowedInputs(gpu::Context& ctx);
  // Room for `lights` records (at least 64).
  void reserve(uint32_t lights);
  ShadowInputs inputs() const;

 private:
  gpu::Context& ctx_;
  gpu::Buffer parameters_;  // zeroed GpuShadows (technique 0)
};

}  // namespace avsm::passes
