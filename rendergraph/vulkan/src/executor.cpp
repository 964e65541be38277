#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <chrono>
#include <optional>

#include "gpu/barriers.h"
#include "gpu/context.h"
#include "gpu/device_limits.h"

static_assert(rg::kWholeSize == VK_WHOLE_SIZE);

namespace rg::vulkan {

using avsm::gpu::Buffer;
using avsm::gpu::Image;

// ------------------------------------------------------------ memory model

static avsm::gpu::ImageDesc image_desc(const TextureDesc& desc, VkImageUsageFlags usage, const std::string& name) {
  avsm::gpu::ImageDesc out;
  out.width = desc.width;
  out.height = desc.height;
  out.depth = desc.depth;
  out.mip_levels = desc.mip_levels;
  out.array_layers = desc.array_layers;
  out.format = desc.format;
  out.usage = usage;
  out.name = name;
  out.sized_by = desc.sized_by;
  return out;
}

static avsm::gpu::BufferDesc buffer_desc(const BufferDesc& desc, VkBufferUsageFlags usage, const std::string& name) {
  return {desc.size, usage, avsm::gpu::MemoryLocation::DeviceLocal, name, desc.sized_by};
}

MemoryRequirements DeviceMemoryModel::texture(const TextureDesc& desc, UsageSet usages, const std::string& name) const {
  auto reqs = avsm::gpu::memory_requirements(ctx_, image_desc(desc, image_usage_flags(usages), name));
  return {reqs.size, reqs.alignment, reqs.memory_type_bits};
}

MemoryRequirements DeviceMemoryModel::buffer(const BufferDesc& desc, UsageSet usages, const std::string& name) const {
  auto reqs = avsm::gpu::memory_requirements(ctx_, buffer_desc(desc, buffer_usage_flags(usages), name));
  return {reqs.size, reqs.alignment, reqs.memory_type_bits};
}

uint64_t DeviceMemoryModel::buffer_image_granularity() const { return ctx_.info().buffer_image_granularity; }

// ------------------------------------------------------------ executor

Executor::Executor(avsm::gpu::Context& ctx, avsm::gpu::TimestampMode timestamps, uint32_t timed_passes)
    : ctx_(ctx), memory_model_(ctx), timer_(ctx, timed_passes, timestamps) {}

Executor::~Executor() = default;

// Bindings belong to one graph: binding a handle of a new graph forgets the old ones.
void Executor::start_binding(uint32_t graph_id) {
  if (graph_id == bound_graph_id_) return;
  imported_images_.clear();
  imported_buffers_.clear();
  bound_graph_id_ = graph_id;
}

void Executor::bind(TextureHandle texture, const Image& image) {
  if (!texture.valid()) throw GraphError("bind: invalid texture handle");
  start_binding(texture.graph_id);
  if (imported_images_.size() <= texture.index) imported_images_.resize(texture.index + 1, nullptr);
  imported_images_[texture.index] = &image;
}

void Executor::bind(BufferHandle buffer, const Buffer& buffer_object) {
  if (!buffer.valid()) throw GraphError("bind: invalid buffer handle");
  start_binding(buffer.graph_id);
  if (imported_buffers_.size() <= buffer.index) imported_buffers_.resize(buffer.index + 1, nullptr);
  imported_buffers_[buffer.index] = &buffer_object;
}

namespace {

template <class T>
const T* carried(const ResourceDecl& resource) {
  const T* const* physical = std::any_cast<const T*>(&resource.physical);
  return physical ? *physical : nullptr;
}

// A buffer import carrying a plain range (its bytes of a VkBuffer the engine does not own).
std::optional<avsm::gpu::BufferRange> carried_range(const ResourceDecl& resource) {
  const auto* range = std::any_cast<avsm::gpu::BufferRange>(&resource.physical);
  if (!range) return std::nullopt;
  if (range->buffer == VK_NULL_HANDLE || range->size == VK_WHOLE_SIZE)
    throw GraphError("imported buffer '" + resource.name +
                     "' carries a range without a VkBuffer or without an explicit size");
  return *range;
}

}  // namespace

TextureHandle import(Graph& graph, std::string name, const Image& image, ImportState initial, ImportState final_state) {
  const avsm::gpu::ImageDesc& d = image.desc();
  return graph.import_texture(std::move(name), {d.width, d.height, d.depth, d.mip_levels, d.array_layers, d.format},
                              initial, final_state, &image);
}

BufferHandle import(Graph& graph, std::string name, const Buffer& buffer, ImportState initial, ImportState final_state) {
  return graph.import_buffer(std::move(name), {buffer.size()}, initial, final_state, &buffer);
}

// The physical resources of the graph's imports: bound, else carried by the import.
void Executor::resolve_imports(const Graph& graph) {
  if (bound_graph_id_ != graph.id()) start_binding(graph.id());
  const std::vector<ResourceDecl>& resources = graph.resources();
  imported_images_.resize(resources.size(), nullptr);
  imported_buffers_.resize(resources.size(), nullptr);
  carried_ranges_.assign(resources.size(), {});
  for (uint32_t i = 0; i < resources.size(); ++i) {
    if (!resources[i].imported) continue;
    if (!imported_images_[i]) imported_images_[i] = carried<Image>(resources[i]);
    if (!imported_buffers_[i]) imported_buffers_[i] = carried<Buffer>(resources[i]);
    if (!imported_buffers_[i]) carried_ranges_[i] = carried_range(resources[i]).value_or(avsm::gpu::BufferRange());
    if (!plan_.resources[i].used) continue;
    const bool found = resources[i].kind == ResourceKind::Texture
                           ? imported_images_[i] != nullptr
                           : imported_buffers_[i] != nullptr || carried_ranges_[i].buffer != VK_NULL_HANDLE;
    if (!found)
      throw GraphError("imported " + std::string(to_string(resources[i].kind)) + " '" + resources[i].name +
                       "' has no physical resource: import it with rg::vulkan::import or call Executor::bind");
  }
}

// What a heap holds, largest first (three at most), with what sizes each: said when the
// heap does not fit the device.
static std::string heap_contents(const CompiledPlan& plan, const PlannedHeap& heap) {
  std::vector<uint32_t> residents = heap.resources;
  std::stable_sort(residents.begin(), residents.end(),
                   [&](uint32_t a, uint32_t b) { return plan.resources[a].size > plan.resources[b].size; });
  std::string contents = "what it holds, largest first:";
  for (size_t i = 0; i < residents.size() && i < 3; ++i) {
    const PlannedResource& r = plan.resources[residents[i]];
    const std::string& sized_by = r.kind == ResourceKind::Texture ? r.texture.sized_by : r.buffer.sized_by;
    contents += (i ? ", '" : " '") + r.name + "' " + avsm::gpu::format_mib(r.size) +
                (sized_by.empty() ? "" : " (" + sized_by + ")");
  }
  return contents;
}

// Creates the heaps and the placed transients of plan_. Called when the plan changes.
void Executor::realise_transients() {
  transient_images_.clear();
  transient_buffers_.clear();
  heaps_.clear();
  for (uint32_t h = 0; h < plan_.heaps.size(); ++h) {
    const PlannedHeap& heap = plan_.heaps[h];
    heaps_.emplace_back(ctx_, heap.size, heap.memory_type_bits, avsm::gpu::MemoryLocation::DeviceLocal,
                        "frame graph heap " + std::to_string(h), heap_contents(plan_, heap));
  }
  transient_images_.resize(plan_.resources.size());
  transient_buffers_.resize(plan_.resources.size());
  for (uint32_t i = 0; i < plan_.resources.size(); ++i) {
    const PlannedResource& r = plan_.resources[i];
    if (r.imported || !r.used || r.heap == kInvalidIndex) continue;
    const avsm::gpu::MemoryHeap& heap = heaps_[r.heap];
    if (r.kind == ResourceKind::Texture)
      transient_images_[i] = std::make_unique<Image>(
          Image::create_placed(ctx_, image_desc(r.texture, r.image_usage, r.name), heap, r.offset));
    else
      transient_buffers_[i] = std::make_unique<Buffer>(
          Buffer::create_placed(ctx_, buffer_desc(r.buffer, r.buffer_usage, r.name), heap, r.offset));
  }
}

void Executor::record_barriers(VkCommandBuffer cmd, const std::vector<Barrier>& barriers) const {
  if (barriers.empty()) return;
  std::vector<VkMemoryBarrier2> memory;
  std::vector<VkBufferMemoryBarrier2> buffers;
  std::vector<VkImageMemoryBarrier2> images;
  for (const Barrier& b : barriers) {
    avsm::gpu::Access src{b.src_stages, b.src_access}, dst{b.dst_stages, b.dst_access};
    if (b.is_global()) {
      memory.push_back(avsm::gpu::make_memory_barrier(src, dst));
      continue;
    }
    const PlannedResource& r = plan_.resources[b.resource];
    if (r.kind == ResourceKind::Texture) {
      VkImageSubresourceRange range{r.aspect, 0, r.texture.mip_levels, 0, r.texture.array_layers};
      images.push_back(avsm::gpu::make_image_barrier(images_[b.resource]->handle(), range, b.old_layout,
                                                     b.new_layout, src, dst));
    } else {
      const avsm::gpu::BufferRange& buffer = buffers_[b.resource];
      VkBufferMemoryBarrier2 barrier = avsm::gpu::make_buffer_barrier(buffer.buffer, src, dst);
      barrier.offset = buffer.offset + b.range.offset;  // a region() starts inside its handle
      // kWholeSize is VK_WHOLE_SIZE, which would run past a region's end.
      barrier.size = b.range.size == VK_WHOLE_SIZE && buffer.offset != 0 ? buffer.size - b.range.offset : b.range.size;
      buffers.push_back(barrier);
    }
  }
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = uint32_t(memory.size());
  dep.pMemoryBarriers = memory.data();
  dep.bufferMemoryBarrierCount = uint32_t(buffers.size());
  dep.pBufferMemoryBarriers = buffers.data();
  dep.imageMemoryBarrierCount = uint32_t(images.size());
  dep.pImageMemoryBarriers = images.data();
  vkCmdPipelineBarrier2(cmd, &dep);
}

void Executor::record(const Graph& graph, VkCommandBuffer cmd, const CompileOptions& options) {
  uint64_t shape = graph.shape_hash(options);
  plan_reused_ = has_plan_ && plan_.shape_hash == shape;
  if (!plan_reused_) {
    has_plan_ = false;  // until its transients exist: a plan the device could not hold is never reused
    plan_ = graph.compile(memory_model_, options);
    realise_transients();
    has_plan_ = true;
  }
  resolve_imports(graph);

  // Physical resource of every plan resource: placed transient or bound import.
  images_.assign(plan_.resources.size(), nullptr);
  buffers_.assign(plan_.resources.size(), {});
  for (uint32_t i = 0; i < plan_.resources.size(); ++i) {
    if (plan_.resources[i].imported) {
      if (i < imported_images_.size()) images_[i] = imported_images_[i];
      if (i < imported_buffers_.size() && imported_buffers_[i]) buffers_[i] = *imported_buffers_[i];
      else if (i < carried_ranges_.size()) buffers_[i] = carried_ranges_[i];
    } else {
      images_[i] = transient_images_[i].get();
      if (transient_buffers_[i]) buffers_[i] = *transient_buffers_[i];
    }
  }

  timer_.begin_frame(cmd, uint32_t(plan_.passes.size()));
  cpu_record_ms_.assign(plan_.passes.size(), 0.0);
  for (uint32_t p = 0; p < plan_.passes.size(); ++p) {
    const PlannedPass& pass = plan_.passes[p];
    auto start = std::chrono::steady_clock::now();
    avsm::gpu::ScopedLabel label(ctx_, cmd, pass.name);
    record_barriers(cmd, pass.barriers);
    uint32_t scope = timer_.begin_scope(cmd, pass.name);
    PassContext context(ctx_, cmd, pass, plan_, images_, buffers_);
    const std::function<void(PassContext&)>& execute = graph.passes()[pass.pass_index].execute;
    if (execute) execute(context);
    timer_.end_scope(cmd, scope);
    cpu_record_ms_[p] = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
  }
  record_barriers(cmd, plan_.final_barriers);
}

std::vector<PassTiming> Executor::read_timings() const {
  std::vector<avsm::gpu::ScopeTiming> scopes = timer_.read_scopes();
  std::vector<PassTiming> out;
  for (uint32_t p = 0; p < plan_.passes.size() && p < scopes.size(); ++p)
    out.push_back({plan_.passes[p].name, plan_.passes[p].queue, scopes[p].gpu_ms, cpu_record_ms_[p]});
  return out;
}

const Image* Executor::transient_image(uint32_t resource) const {
  return resource < transient_images_.size() ? transient_images_[resource].get() : nullptr;
}

const Buffer* Executor::transient_buffer(uint32_t resource) const {
  return resource < transient_buffers_.size() ? transient_buffers_[resource].get() : nullptr;
}

}  // namespace rg::vulkan
