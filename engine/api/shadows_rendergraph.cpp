// The rendergraph adapter of the pass list: each listed pass becomes a graph pass that
// declares the list's uses and records through the list's record function. It knows
// nothing of the shadow passes themselves; the list is all it reads.
#include "avsm/shadows_rendergraph.h"

#include <rendergraph/vulkan/pass_context.h>

#include <memory>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/resources.h"

namespace avsm {
namespace {

rg::QueueType to_rg(PassQueue queue) {
  switch (queue) {
    case PassQueue::graphics: return rg::QueueType::Graphics;
    case PassQueue::compute: return rg::QueueType::Compute;
    case PassQueue::transfer: return rg::QueueType::Transfer;
  }
  return rg::QueueType::Graphics;
}

rg::ImportState to_rg(const PassResourceState& state) { return {state.stages, state.access, state.layout}; }

// A usage by the name the list gives it (the usage table's own names).
rg::Usage usage_named(const std::string& name, const ShadowPass& pass) {
  for (uint32_t i = 0; i < rg::kUsageCount; ++i)
    if (name == rg::to_string(rg::Usage(i))) return rg::Usage(i);
  throw std::invalid_argument("avsm::add_to_graph: pass '" + pass.name + "' uses a resource as '" + name +
                              "', which is not a usage of the frame graph");
}

// A list resource's handle in the graph, as of the latest version declared.
struct Declared {
  bool exists = false;
  rg::TextureHandle texture;
  rg::BufferHandle buffer;
};

// Imports persistent resource `index` into `graph` the first time it is needed.
Declared& declared_persistent(rg::Graph& graph, const ShadowPassList& list, std::vector<Declared>& declared,
                              uint32_t index) {
  Declared& d = declared.at(index);
  if (d.exists) return d;
  const PassResource& r = list.resources[index];
  if (r.kind != PassResource::Kind::buffer)
    throw std::invalid_argument("avsm::add_to_graph: persistent resource '" + r.name +
                                "' is an image; the list's persistent resources are buffers");
  d.buffer = graph.import_buffer(r.name, {r.buffer.size, r.sized_by}, to_rg(r.initial), to_rg(r.final_state),
                                 gpu::BufferRange(r.handle, r.buffer.size, r.offset));
  d.exists = true;
  return d;
}

// Declares one use in a pass's setup: read-only usages first, then the one that writes
// (a pass uses nothing after writing it). Updates `d` to the version after the pass.
void declare_use(rg::PassBuilder& b, const ShadowPass& pass, const PassResourceUse& use, const PassResource& r,
                 Declared& d) {
  const rg::QueueType queue = to_rg(pass.queue);
  const rg::BufferRange range{use.offset, use.size};
  std::vector<rg::Usage> reads, writes;
  for (const std::string& name : use.usages) {
    const rg::Usage usage = usage_named(name, pass);
    (rg::usage_info(usage, queue).is_write ? writes : reads).push_back(usage);
  }
  const bool image = r.kind == PassResource::Kind::image;
  for (rg::Usage usage : reads) {
    if (image) d.texture = b.read(d.texture, usage);
    else d.buffer = b.read(d.buffer, usage, range);
  }
  for (rg::Usage usage : writes) {
    if (image) d.texture = use.reads ? b.read_write(d.texture, usage) : b.write(d.texture, usage);
    else d.buffer = use.reads ? b.read_write(d.buffer, usage, range) : b.write(d.buffer, usage, range);
  }
}

ShadowInputs inputs_of(const ShadowLookupResources& lookup, const FogLookupResources& fog,
                       const std::vector<Declared>& declared) {
  auto range = [](const PassBufferRange& r) {
    return r.buffer ? gpu::BufferRange(r.buffer, r.size, r.offset) : gpu::BufferRange();
  };
  ShadowInputs inputs;
  inputs.parameters = lookup.parameters.buffer;
  if (lookup.records != kNoPassResource) inputs.records = declared.at(lookup.records).buffer;
  for (uint32_t map : lookup.maps) inputs.maps.push_back(declared.at(map).buffer);
  for (uint32_t list : lookup.lists) inputs.lists.push_back(declared.at(list).buffer);
  inputs.atlas = range(lookup.atlas);
  inputs.list_heads = range(lookup.list_heads);
  inputs.list_nodes = range(lookup.list_nodes);
  if (lookup.page_requests != kNoPassResource) {
    inputs.page_requests = declared.at(lookup.page_requests).buffer;
    inputs.page_request_bits = range(lookup.page_request_bits);
  }
  inputs.unused_buffer = lookup.unused_buffer;
  inputs.frame_slot = lookup.frame_slot;
  if (fog.integrated != kNoPassResource) inputs.fog_grid = declared.at(fog.integrated).buffer;
  inputs.fog_parameters = range(fog.parameters);
  inputs.fog_grid_bytes = range(fog.grid);
  return inputs;
}

}  // namespace

ShadowInputs add_to_graph(rg::Graph& graph, const ShadowPassList& list) {
  std::vector<Declared> declared(list.resources.size());
  for (const ShadowPass& pass : list.passes) {
    for (const PassResourceUse& use : pass.uses)
      if (!list.resources.at(use.resource).transient) declared_persistent(graph, list, declared, use.resource);
    // The handles this pass resolves when it runs (their indices are what matter).
    auto used = std::make_shared<std::vector<Declared>>(pass.uses.size());
    graph.add_pass(
        pass.name, to_rg(pass.queue),
        [&](rg::PassBuilder& b) {
          for (size_t u = 0; u < pass.uses.size(); ++u) {
            const PassResourceUse& use = pass.uses[u];
            const PassResource& r = list.resources[use.resource];
            Declared& d = declared[use.resource];
            if (!d.exists && r.kind == PassResource::Kind::image)
              d.texture = b.create_texture(r.name, {r.image.width, r.image.height, r.image.depth, r.image.mip_levels,
                                                    r.image.array_layers, r.image.format, r.sized_by});
            else if (!d.exists)
              d.buffer = b.create_buffer(r.name, {r.buffer.size, r.sized_by});
            d.exists = true;
            declare_use(b, pass, use, r, d);
            (*used)[u] = d;
          }
          if (pass.side_effect) b.side_effect();
        },
        [record = pass.record, uses = pass.uses, used, count = list.resources.size()](rg::PassContext& c) {
          std::vector<ResolvedResource> resolved(count);
          for (size_t u = 0; u < uses.size(); ++u) {
            const Declared& d = (*used)[u];
            ResolvedResource& r = resolved[uses[u].resource];
            if (d.texture.valid()) {
              r.image = c.image(d.texture);
              r.view = c.view(d.texture);
            } else {
              const gpu::BufferRange buffer = c.buffer(d.buffer);
              r.buffer = buffer.buffer;
              r.offset = buffer.offset;
            }
          }
          record(c.cmd(), resolved);
        });
  }
  // What the shading reads but no pass of this frame touched is imported as it is.
  for (uint32_t index : list.lookup.maps) declared_persistent(graph, list, declared, index);
  for (uint32_t index : list.lookup.lists) declared_persistent(graph, list, declared, index);
  if (list.lookup.records != kNoPassResource) declared_persistent(graph, list, declared, list.lookup.records);
  if (list.lookup.page_requests != kNoPassResource)
    declared_persistent(graph, list, declared, list.lookup.page_requests);
  return inputs_of(list.lookup, list.fog, declared);
}

ShadowInputs add_to_graph(rg::Graph& graph, Shadows& shadows, const Camera& camera, const ShadowCasters& casters,
                          uint32_t frame_slot) {
  return add_to_graph(graph, shadows.pass_list(camera, casters, frame_slot));
}

ShadowInputs unshadowed_inputs(const Shadows& shadows) { return inputs_of(shadows.unshadowed_lookup(), {}, {}); }

}  // namespace avsm
