#pragma once
// Declaring a frame: passes, the resources they create or import, and how they use them.
//
//   rg::Graph graph;
//   auto shadow = graph.import_texture("shadow_map", desc, rg::ImportState::of(rg::Usage::Sampled),
//                                      rg::ImportState::of(rg::Usage::Sampled));
//   graph.add_pass("shadow", rg::QueueType::Graphics,
//       [&](rg::PassBuilder& b) { shadow = b.write(shadow, rg::Usage::DepthAttachmentWrite); },
//       [](rg::PassContext&) { /* record commands */ });
//   rg::CompiledPlan plan = graph.compile(memory_model);
//
// Setup runs inside add_pass, so a pass can only use versions that already exist: the
// declaration order is always a valid execution order and the graph cannot have cycles.
#include <rendergraph/plan.h>

#include <any>
#include <cstdint>
#include <functional>
#include <memory>
#include <string>
#include <vector>

namespace rg {

class Graph;

// One pass's use of one resource (or of one range of a buffer). A pass accesses each
// resource through one AccessDecl per range; several read usages (or a read and a write
// with the same layout) of the same range are merged into it. Ranges of one buffer used
// by one pass are disjoint.
struct AccessDecl {
  uint32_t resource = kInvalidIndex;
  BufferRange range;  // buffers: whole() or a proper sub-range with an explicit size
  UsageSet usages;
  bool reads = false;   // depends on the previous contents (read / read_write)
  bool writes = false;  // produces a new version (write / read_write)
  uint32_t read_version = 0;
  uint32_t written_version = 0;
};

struct PassDecl {
  std::string name;
  QueueType queue = QueueType::Graphics;
  std::vector<AccessDecl> accesses;
  bool side_effect = false;
  std::function<void(PassContext&)> execute;
};

struct ResourceDecl {
  std::string name;
  ResourceKind kind = ResourceKind::Texture;
  TextureDesc texture;
  BufferDesc buffer;
  bool imported = false;
  ImportState initial;
  ImportState final_state;
  // Imported only: the physical resource behind it, as the executor knows it (for the
  // Vulkan executor a const avsm::gpu::Image* or const avsm::gpu::Buffer*). The graph
  // only carries it, so declaring a frame needs no executor (rg::vulkan::import).
  std::any physical;
  uint32_t created_by = kInvalidIndex;  // pass whose setup created it; kInvalidIndex if imported
  std::vector<uint32_t> writers;        // writers[v] = pass that produced version v (v0: none)

  uint32_t current_version() const { return static_cast<uint32_t>(writers.size()) - 1; }
};

struct OutputDecl {
  uint32_t resource = kInvalidIndex;
  uint32_t version = 0;
};

// Handed to a pass's setup function. Every call checks its handle (stale version,
// other graph, default-constructed) and throws GraphError naming pass and resource.
class PassBuilder {
 public:
  // Transient resources: owned by the graph, placed in shared heaps, may alias.
  TextureHandle create_texture(std::string name, const TextureDesc& desc);
  BufferHandle create_buffer(std::string name, const BufferDesc& desc);

  // Read the current contents; `usage` must not write. Returns the same handle.
  TextureHandle read(TextureHandle texture, Usage usage);
  BufferHandle read(BufferHandle buffer, Usage usage, BufferRange range = {});
  // Overwrite without reading the previous contents; returns the new version.
  TextureHandle write(TextureHandle texture, Usage usage);
  BufferHandle write(BufferHandle buffer, Usage usage, BufferRange range = {});
  // Read and modify in place (atomics, blending onto existing contents, load-op LOAD);
  // returns the new version.
  TextureHandle read_write(TextureHandle texture, Usage usage);
  BufferHandle read_write(BufferHandle buffer, Usage usage, BufferRange range = {});
  //
  // Buffer ranges: the barrier planner tracks each range on its own, so passes touching
  // disjoint ranges of one buffer need no barrier between them. A write of a range keeps
  // the rest of the buffer (the new version depends on the previous one). One pass may
  // use several disjoint ranges of a buffer, reads before its one write.

  // The pass has effects outside the graph (readback, debug output): never cull it.
  void side_effect();

 private:
  friend class Graph;
  PassBuilder(Graph& graph, uint32_t pass) : graph_(graph), pass_(pass) {}

  uint32_t access(ResourceKind kind, uint32_t index, uint32_t version, uint32_t graph_id, Usage usage,
                  bool reads, bool writes, BufferRange range = {});
  // The declared range in canonical form (whole(), or explicit size); throws when it
  // leaves the buffer or is empty.
  BufferRange checked_range(const ResourceDecl& resource, BufferRange range) const;
  // The slot of this pass's access to `range` of `resource` (merging identical ranges),
  // or a new one; throws when it overlaps another range of the resource in this pass.
  uint32_t access_slot(const ResourceDecl& resource, uint32_t index, BufferRange range);
  uint32_t create(std::string name, ResourceKind kind, const TextureDesc& texture, const BufferDesc& buffer);

  Graph& graph_;
  uint32_t pass_;
};

class Graph {
 public:
  Graph();
  Graph(Graph&&) noexcept = default;
  Graph& operator=(Graph&&) noexcept = default;
  Graph(const Graph&) = delete;
  Graph& operator=(const Graph&) = delete;

  // Runs `setup` immediately; stores `execute` for the executor (the core never calls it).
  // After a GraphError thrown from setup the graph is in an unspecified state: discard it.
  void add_pass(std::string name, QueueType queue, std::function<void(PassBuilder&)> setup,
                std::function<void(PassContext&)> execute);

  // Typed form (Filament-style): `setup(PassBuilder&, Data&)` fills a Data with the
  // handles the pass uses; `execute(const Data&, PassContext&)` reads them when the
  // executor runs the pass. The Data lives as long as the graph; the returned reference
  // lets later passes read this pass's output handles.
  template <class Data, class Setup, class Execute>
  const Data& add_pass(std::string name, QueueType queue, Setup&& setup, Execute&& execute) {
    auto data = std::make_shared<Data>();
    add_pass(
        std::move(name), queue, [&](PassBuilder& builder) { setup(builder, *data); },
        [data, execute = std::forward<Execute>(execute)](PassContext& context) { execute(*data, context); });
    return *data;
  }

  // External/persistent resources (swapchain image, maps kept across frames, history).
  // `initial` is their state before the graph; the plan leaves them in `final_state`.
  // Writes to imported resources are visible outside the graph, so they anchor culling.
  // `physical` is the resource itself, for the executor (see ResourceDecl::physical).
  TextureHandle import_texture(std::string name, const TextureDesc& desc, ImportState initial,
                               ImportState final_state, std::any physical = {});
  BufferHandle import_buffer(std::string name, const BufferDesc& desc, ImportState initial,
                             ImportState final_state, std::any physical = {});

  // Keep the producer of this version (and what it depends on) even if no pass reads it,
  // and keep a transient's memory intact until the end of the graph.
  void mark_output(TextureHandle texture);
  void mark_output(BufferHandle buffer);

  // validate -> cull -> order -> lifetimes -> memory plan -> barrier plan -> plan.
  // Throws GraphError for invalid declarations. Pure computation: no Vulkan calls.
  CompiledPlan compile(const MemoryModel& memory, const CompileOptions& options = {}) const;

  // Hash of everything that shapes the plan (passes, names, queues, descs, accesses,
  // imports, outputs, options), but not the execute callbacks. The memory model is
  // assumed fixed per device. Equal hashes: the executor may reuse last frame's plan,
  // calling this graph's execute callbacks through PlannedPass::pass_index.
  uint64_t shape_hash(const CompileOptions& options = {}) const;

  // The declaration, read-only (used by the compiler phases, the executor, tests).
  uint32_t id() const { return id_; }
  const std::vector<PassDecl>& passes() const { return passes_; }
  const std::vector<ResourceDecl>& resources() const { return resources_; }
  const std::vector<OutputDecl>& outputs() const { return outputs_; }

 private:
  friend class PassBuilder;

  uint32_t import_resource(std::string name, ResourceKind kind, const TextureDesc& texture,
                           const BufferDesc& buffer, ImportState initial, ImportState final_state);
  void mark_output(ResourceKind kind, uint32_t index, uint32_t version, uint32_t graph_id);
  // Handle checks; `pass` names the culprit in messages (kInvalidIndex: mark_output).
  const ResourceDecl& resolve(uint32_t pass, ResourceKind kind, uint32_t index, uint32_t graph_id) const;
  void check_version(uint32_t pass, const ResourceDecl& resource, uint32_t version) const;
  std::string who(uint32_t pass) const;

  uint32_t id_;
  std::vector<PassDecl> passes_;
  std::vector<ResourceDecl> resources_;
  std::vector<OutputDecl> outputs_;
  // Where each resource was last accessed, so a pass merges repeated accesses in O(1).
  struct LastAccess {
    uint32_t pass = kInvalidIndex;
    uint32_t slot = 0;  // index into that pass's accesses
  };
  std::vector<LastAccess> last_access_;
};

}  // namespace rg
