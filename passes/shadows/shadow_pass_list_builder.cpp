#include "passes/shadows/shadow_pass_list_builder.h"

#include <rendergraph/vulkan/pass_context.h>

#include <any>
#include <memory>
#include <stdexcept>

#include "gpu/resources.h"
#include "passes/camera/fog/fog_media.h"
#include "passes/shadows/shadow_maps.h"

namespace avsm::passes {

const char* to_string(PassQueue queue) {
  switch (queue) {
    case PassQueue::graphics: return "graphics";
    case PassQueue::compute: return "compute";
    case PassQueue::transfer: return "transfer";
  }
  return "?";
}

namespace {

PassQueue to_pass_queue(rg::QueueType queue) {
  switch (queue) {
    case rg::QueueType::Graphics: return PassQueue::graphics;
    case rg::QueueType::Compute: return PassQueue::compute;
    case rg::QueueType::Transfer: return PassQueue::transfer;
  }
  return PassQueue::graphics;
}

PassResourceState state_of(const rg::ImportState& state) { return {state.stages, state.access, state.layout}; }

// What the record functions of one list share: the declarations as a plan of the
// graph's own (names, descriptions and each pass's accesses, which a PassContext reads),
// the persistent buffers, and the device to record with.
struct RecordedFrame {
  rg::CompiledPlan plan;                     // resources and passes, by graph index
  std::vector<gpu::BufferRange> persistent;  // by resource index; empty for transients
  const gpu::Context* ctx = nullptr;
};

// The bytes an imported buffer occupies, from the gpu::Buffer its import carries.
gpu::BufferRange persistent_range(const rg::ResourceDecl& resource) {
  const gpu::Buffer* const* buffer = std::any_cast<const gpu::Buffer*>(&resource.physical);
  if (resource.kind != rg::ResourceKind::Buffer || !buffer)
    throw std::logic_error("shadow pass list: imported " + std::string(rg::to_string(resource.kind)) + " '" +
                           resource.name + "' does not carry a gpu::Buffer; only buffers are persistent here");
  return **buffer;
}

PassResource listed_resource(const rg::ResourceDecl& decl, rg::UsageSet usages, const gpu::BufferRange& persistent) {
  PassResource r;
  r.name = decl.name;
  r.transient = !decl.imported;
  if (decl.kind == rg::ResourceKind::Texture) {
    const rg::TextureDesc& t = decl.texture;
    r.kind = PassResource::Kind::image;
    r.image = {t.width, t.height, t.depth, t.mip_levels, t.array_layers, t.format, rg::image_usage_flags(usages)};
    r.sized_by = t.sized_by;
  } else {
    r.kind = PassResource::Kind::buffer;
    r.buffer = {decl.buffer.size, rg::buffer_usage_flags(usages)};
    r.sized_by = decl.buffer.sized_by;
  }
  if (decl.imported) {
    r.handle = persistent.buffer;
    r.offset = persistent.offset;
    r.initial = state_of(decl.initial);
    r.final_state = state_of(decl.final_state);
  }
  return r;
}

// One access in Vulkan terms: every usage it merges, through the usage table.
rg::PlannedAccess planned_access(const rg::AccessDecl& a, rg::QueueType queue, rg::ResourceKind kind) {
  rg::PlannedAccess planned{a.resource, a.range, a.usages, a.reads, a.writes, a.read_version, a.written_version};
  a.usages.for_each([&](rg::Usage usage) {
    const rg::UsageInfo info = rg::usage_info(usage, queue);
    planned.stages |= info.stages;
    planned.access |= info.access;
    if (kind == rg::ResourceKind::Texture) planned.layout = info.layout;  // merged usages share one layout
  });
  return planned;
}

PassResourceUse listed_use(const rg::PlannedAccess& a) {
  PassResourceUse use;
  use.resource = a.resource;
  use.offset = a.range.offset;
  use.size = a.range.size;  // rg::kWholeSize is VK_WHOLE_SIZE
  use.reads = a.reads;
  use.writes = a.writes;
  a.usages.for_each([&](rg::Usage usage) { use.usages.push_back(rg::to_string(usage)); });
  use.stages = a.stages;
  use.access = a.access;
  use.layout = a.layout;
  return use;
}

// Pass `p` of `frame` on the resources the host resolved: each of its resources becomes
// what a PassContext resolves (the list's own buffer for persistent ones), then the
// pass's own execute step records.
void record_pass(const RecordedFrame& frame, uint32_t p, const std::function<void(rg::PassContext&)>& execute,
                 VkCommandBuffer cmd, const std::vector<ResolvedResource>& resolved) {
  const rg::PlannedPass& pass = frame.plan.passes[p];
  if (!frame.ctx)
    throw std::logic_error("shadow pass '" + pass.name + "': this pass list was made without a device to record with");
  const size_t count = frame.plan.resources.size();
  std::vector<const gpu::Image*> images(count, nullptr);
  std::vector<gpu::BufferRange> buffers(count);
  std::vector<gpu::Image> borrowed;  // the host's images, as the pass reads them
  borrowed.reserve(pass.accesses.size());
  for (const rg::PlannedAccess& a : pass.accesses) {
    const rg::PlannedResource& r = frame.plan.resources[a.resource];
    const ResolvedResource given = a.resource < resolved.size() ? resolved[a.resource] : ResolvedResource{};
    auto require = [&](bool holds, const std::string& what) {
      if (!holds)
        throw std::invalid_argument("avsm::ShadowPass::record: pass '" + pass.name + "': " +
                                    (r.imported ? "persistent " : "transient ") + rg::to_string(r.kind) + " '" +
                                    r.name + "' " + what);
    };
    if (r.imported) {
      const gpu::BufferRange& ours = frame.persistent[a.resource];
      require(given.buffer == VK_NULL_HANDLE || (given.buffer == ours.buffer && given.offset == ours.offset),
              "was resolved to another buffer or offset than the list's own (leave it empty, or give the list's)");
      buffers[a.resource] = ours;
    } else if (r.kind == rg::ResourceKind::Texture) {
      require(given.image != VK_NULL_HANDLE && given.view != VK_NULL_HANDLE,
              "has no VkImage or VkImageView (resolve every transient the pass uses)");
      const rg::TextureDesc& t = r.texture;
      gpu::ImageDesc desc{t.width, t.height, t.depth, t.mip_levels, t.array_layers, false, t.format, 0, r.name, {}};
      borrowed.push_back(gpu::Image::borrow(*frame.ctx, given.image, given.view, desc));
      images[a.resource] = &borrowed.back();
    } else {
      require(given.buffer != VK_NULL_HANDLE, "has no VkBuffer (resolve every transient the pass uses)");
      buffers[a.resource] = gpu::BufferRange(given.buffer, r.buffer.size, given.offset);
    }
  }
  rg::PassContext context(*frame.ctx, cmd, pass, frame.plan, images, buffers);
  if (execute) execute(context);
}

}  // namespace

ShadowPassList pass_list_of(const rg::Graph& graph, const gpu::Context* ctx) {
  const std::vector<rg::ResourceDecl>& resources = graph.resources();
  auto frame = std::make_shared<RecordedFrame>();
  frame->ctx = ctx;
  frame->persistent.resize(resources.size());

  std::vector<rg::UsageSet> usages(resources.size());  // every use of each: a transient's creation flags
  for (const rg::PassDecl& pass : graph.passes())
    for (const rg::AccessDecl& a : pass.accesses) usages[a.resource].insert(a.usages);

  ShadowPassList list;
  for (uint32_t i = 0; i < resources.size(); ++i) {
    const rg::ResourceDecl& decl = resources[i];
    if (decl.imported) frame->persistent[i] = persistent_range(decl);
    list.resources.push_back(listed_resource(decl, usages[i], frame->persistent[i]));
    rg::PlannedResource planned;
    planned.name = decl.name;
    planned.kind = decl.kind;
    planned.texture = decl.texture;
    planned.buffer = decl.buffer;
    planned.imported = decl.imported;
    frame->plan.resources.push_back(std::move(planned));
  }
  for (uint32_t p = 0; p < graph.passes().size(); ++p) {
    const rg::PassDecl& decl = graph.passes()[p];
    rg::PlannedPass planned{decl.name, decl.queue, p, {}, {}};
    ShadowPass pass{decl.name, to_pass_queue(decl.queue), {}, decl.side_effect, {}};
    for (const rg::AccessDecl& a : decl.accesses) {
      planned.accesses.push_back(planned_access(a, decl.queue, resources[a.resource].kind));
      pass.uses.push_back(listed_use(planned.accesses.back()));
    }
    frame->plan.passes.push_back(std::move(planned));
    pass.record = [frame, p, execute = decl.execute](VkCommandBuffer cmd, const std::vector<ResolvedResource>& resolved) {
      record_pass(*frame, p, execute, cmd, resolved);
    };
    list.passes.push_back(std::move(pass));
  }
  return list;
}

ShadowLookupResources lookup_of(const ShadowInputs& inputs) {
  auto range = [](const gpu::BufferRange& r) { return PassBufferRange{r.buffer, r.offset, r.size}; };
  ShadowLookupResources lookup;
  if (inputs.records.valid()) lookup.records = inputs.records.index;
  for (rg::BufferHandle map : inputs.maps) lookup.maps.push_back(map.index);
  for (rg::BufferHandle list : inputs.lists) lookup.lists.push_back(list.index);
  lookup.parameters = {inputs.parameters, 0, VK_WHOLE_SIZE};
  lookup.atlas = range(inputs.atlas);
  lookup.list_heads = range(inputs.list_heads);
  lookup.list_nodes = range(inputs.list_nodes);
  if (inputs.page_requests.valid()) {
    lookup.page_requests = inputs.page_requests.index;
    lookup.page_request_bits = range(inputs.page_request_bits);
  }
  lookup.unused_buffer = inputs.unused_buffer;
  lookup.frame_slot = inputs.frame_slot;
  return lookup;
}

ShadowPassList describe_shadow_frame(ShadowMaps& maps, const gpu::Context& ctx, const View& camera,
                                     const ShadowCasters& casters, uint32_t slot) {
  rg::Graph graph;
  const ShadowInputs inputs = maps.add_to_graph(graph, camera, casters, slot);
  ShadowPassList list = pass_list_of(graph, &ctx);
  list.lookup = lookup_of(inputs);
  return list;
}

FogLookupResources fog_lookup_of(const FogInputs& inputs) {
  auto range = [](const gpu::BufferRange& r) { return PassBufferRange{r.buffer, r.offset, r.size}; };
  const PassBufferRange parameters = range(*inputs.parameters);
  FogLookupResources fog{kNoPassResource, parameters, parameters};
  if (inputs.enabled()) {
    fog.integrated = inputs.integrated.index;
    fog.grid = range(*inputs.integrated_buffer);
  }
  return fog;
}

}  // namespace avsm::passes
