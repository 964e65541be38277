// ShadowMaps' frame: the passes declared per map (capture lists, the technique's build or
// the fixed build, the copies of the lists that lookups read) and what a map's casters are.
#include <rendergraph/vulkan/executor.h>
#include <rendergraph/vulkan/pass_context.h>

#include <algorithm>
#include <stdexcept>

#include "passes/shadows/shadow_maps.h"

namespace avsm::passes {

ShadowInputs ShadowMaps::add_to_graph(rg::Graph& graph, const View& camera, const ShadowCasters& casters,
                                      uint32_t slot) {
  if (slot >= frames_in_flight())
    throw std::invalid_argument("ShadowMaps: frame slot " + std::to_string(slot) + " of " +
                                std::to_string(frames_in_flight()) + " frames in flight");
  retired_.declared(slot);
  ShadowInputs inputs = unshadowed_inputs();
  inputs.frame_slot = slot;
  if (lights_.empty()) return inputs;
  update_views(camera);
  inputs.parameters = parameters_[slot].handle();
  inputs.records = add_parameter_upload(graph, camera, slot);
  inputs.atlas = atlas_ ? gpu::BufferRange(atlas_) : gpu::BufferRange();
  inputs.list_heads = list_heads_ ? gpu::BufferRange(list_heads_) : gpu::BufferRange();
  inputs.list_nodes = list_nodes_ ? gpu::BufferRange(list_nodes_) : gpu::BufferRange();
  if (page_requests_) {
    inputs.page_requests = add_page_requests_clear(graph, slot);
    inputs.page_request_bits = page_requests_[slot];
  }
  for (MapState& map : maps_) {
    const LightState& light = lights_[map.light];
    if (map.pages) {
      add_page_builds(graph, map, casters, slot, inputs);
      continue;
    }
    ++map.revision;  // a dense map is built every frame
    const scene::ShadowSettings& settings = light.light.shadow;
    const ShadowCasters map_casters = casters_of(map, casters);
    const bool fixed = settings.build == scene::ShadowBuild::fixed;
    const TechniqueBuilder& builder = *builders_[light.technique->code() - 1];
    // The fixed build needs no lists; they are still captured for lookups that read them
    // (the uncompressed reference).
    std::optional<CaptureLists> lists;
    DeclaredMap& declared = map.declared[slot];
    declared = {map.capacity, map.map_state, !fixed || map.lookups_read_lists, map_casters.strands.segment_count};
    if (declared.captured_lists) lists = add_capture_lists(graph, map, map_casters, slot);
    if (map.lookups_read_lists) add_list_copy(graph, map, *lists, inputs);
    if (!light.technique->has_map()) continue;
    // The map persists from frame to frame: this frame's build waits for the previous one's lookups.
    rg::BufferHandle handle = rg::vulkan::import(graph, map.prefix + " " + settings.technique + " map", map.map,
                                                 rewritten_after(map_state_after_frame()), map_state_after_frame());
    if (fixed) {
      rg::BufferHandle counter = rg::vulkan::import(graph, map.prefix + " fixed build counter", map.fixed_counter[slot],
                                                    rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
      inputs.maps.push_back(builder.add_fixed_to_graph({graph, map.prefix, handle, counter, map.view, settings,
                                                        map.map_state, map_casters, options_.smoke_samples_per_segment}));
    } else {
      inputs.maps.push_back(
          builder.add_to_graph({graph, map.prefix, *lists, handle, map.view, settings, map.map_state}, *lists));
    }
  }
  return inputs;
}

// A map's capture lists: cleared, every caster appended, sorted if its settings ask.
CaptureLists ShadowMaps::add_capture_lists(rg::Graph& graph, const MapState& map, const ShadowCasters& casters,
                                           uint32_t slot) const {
  const scene::ShadowSettings& settings = lights_[map.light].light.shadow;
  rg::BufferHandle counter = rg::vulkan::import(graph, map.prefix + " capture counter", map.counter[slot],
                                                rg::ImportState::none(), rg::ImportState::of(rg::Usage::HostRead));
  const std::vector<LightView> views = map.virtual_views.empty() ? std::vector<LightView>{map.view} : map.virtual_views;
  return add_capture_lists(graph, map.prefix, map.view.resolution, views, settings.sort, map.capacity, counter, casters);
}

// The lists of a map, a page of a paged map, or an area light's virtual lights (each a
// range of the lists' texels: one pass per caster kind draws them all).
CaptureLists ShadowMaps::add_capture_lists(rg::Graph& graph, const std::string& prefix, uint32_t resolution,
                                           const std::vector<LightView>& views, bool sort, uint64_t capacity,
                                           rg::BufferHandle counter, const ShadowCasters& casters) const {
  CaptureLists lists = add_capture_clear_pass(graph, prefix, resolution, capacity, counter);
  lists = capture_opaque_.add_to_graph(graph, prefix, lists, views, casters.meshes);
  lists = capture_hair_.add_to_graph(graph, prefix, lists, views, casters.strands);
  lists = capture_smoke_.add_to_graph(graph, prefix, lists, views, casters.volumes, options_.smoke_samples_per_segment);
  if (sort) lists = sort_.add_to_graph(graph, prefix, lists, resolution);
  return lists;
}

// "<map> copy lists": the heads and nodes into the map's regions of the looked-up list
// buffers, which every camera pass binds whole.
void ShadowMaps::add_list_copy(rg::Graph& graph, const MapState& map, const CaptureLists& lists,
                               ShadowInputs& inputs) const {
  add_list_copy(graph, map.prefix, lists, map.list_heads, map.list_nodes, map.view.resolution,
                map.capacity * kCaptureSegmentBytes, inputs);
}

// The same into regions `target_heads` and `target_nodes` (of the looked-up list buffers)
// of lists captured at `resolution`, `node_bytes` of their nodes.
void ShadowMaps::add_list_copy(rg::Graph& graph, const std::string& prefix, const CaptureLists& lists,
                               const gpu::Buffer& target_heads, const gpu::Buffer& target_nodes, uint32_t resolution,
                               uint64_t node_bytes, ShadowInputs& inputs) const {
  const rg::ImportState after = rg::ImportState::of(rg::Usage::StorageRead);
  rg::BufferHandle heads = rg::vulkan::import(graph, prefix + " looked-up list heads", target_heads,
                                              rewritten_after(after), after);
  rg::BufferHandle nodes = rg::vulkan::import(graph, prefix + " looked-up list nodes", target_nodes,
                                              rewritten_after(after), after);
  struct Data {
    rg::TextureHandle source_heads;
    rg::BufferHandle source_nodes, heads, nodes;
  };
  const Data& copy = graph.add_pass<Data>(prefix + " copy lists", rg::QueueType::Transfer,
      [&](rg::PassBuilder& b, Data& d) {
        d.source_heads = b.read(lists.heads, rg::Usage::TransferSrc);
        d.source_nodes = b.read(lists.nodes, rg::Usage::TransferSrc);
        d.heads = b.write(heads, rg::Usage::TransferDst);
        d.nodes = b.write(nodes, rg::Usage::TransferDst);
      },
      [resolution, node_bytes](const Data& d, rg::PassContext& c) {
        const gpu::BufferRange heads = c.buffer(d.heads), nodes = c.buffer(d.nodes), source = c.buffer(d.source_nodes);
        VkBufferImageCopy image_copy{};
        image_copy.bufferOffset = heads.offset;
        image_copy.imageSubresource = {VK_IMAGE_ASPECT_COLOR_BIT, 0, 0, 1};
        image_copy.imageExtent = {resolution, resolution, 1};
        vkCmdCopyImageToBuffer(c.cmd(), c.image(d.source_heads), c.layout(d.source_heads), heads, 1, &image_copy);
        const VkBufferCopy node_copy{source.offset, nodes.offset, node_bytes};
        vkCmdCopyBuffer(c.cmd(), source, nodes, 1, &node_copy);
      });
  inputs.lists.push_back(copy.heads);
  inputs.lists.push_back(copy.nodes);
}

// The casters a map takes: all of them, or its cluster's.
ShadowCasters ShadowMaps::casters_of(const MapState& map, const ShadowCasters& all) const {
  return map.objects ? select_casters(all, *map.objects) : all;
}

// The casters of `objects` (indices into objects_) out of `all`.
ShadowCasters ShadowMaps::select_casters(const ShadowCasters& all, const std::vector<uint32_t>& objects) const {
  ShadowCasters casters = all;
  casters.meshes.draws.clear();
  casters.strands.segment_count = 0;
  casters.volumes.volume_mask = 0;
  uint32_t first_segment = ~0u, end_segment = 0;
  bool unmasked_volume = false;  // volumes from kMaxClusteredVolumes on cast whatever the mask
  for (uint32_t object : objects) {
    const CasterObject& o = objects_.at(object);
    switch (o.kind) {
      case CasterObject::Kind::mesh_draw:
        if (o.first < all.meshes.draws.size()) casters.meshes.draws.push_back(all.meshes.draws[o.first]);
        break;
      case CasterObject::Kind::strands:
        first_segment = std::min(first_segment, o.first);
        end_segment = std::max(end_segment, o.first + o.count);
        break;
      case CasterObject::Kind::volume:
        if (o.first < kMaxClusteredVolumes) casters.volumes.volume_mask |= 1u << o.first;
        else unmasked_volume = true;
        break;
    }
  }
  // One range of segments: a cluster's grooms are contiguous (cluster_casters()); a
  // page's grooms take the segments between them too, which cast nothing on it.
  if (end_segment > first_segment && first_segment < all.strands.segment_count) {
    casters.strands.first_segment = first_segment;
    casters.strands.segment_count = std::min(end_segment, all.strands.segment_count) - first_segment;
  }
  if (casters.volumes.volume_mask == 0 && !unmasked_volume) casters.volumes.volume_count = 0;
  return casters;
}

}  // namespace avsm::passes
