// Graph declaration: passes, resources, versioned handles. Everything that can only be
// checked at the call (is this handle still current?) is checked here; everything about
// the declaration as a whole is checked by the validate phase at compile time.
#include <rendergraph/graph.h>

#include <atomic>
#include <string>

namespace rg {
namespace {

uint32_t next_graph_id() {
  static std::atomic<uint32_t> counter{0};
  return ++counter;  // 0 stays free for default-constructed handles
}

}  // namespace

Graph::Graph() : id_(next_graph_id()) {}

void Graph::add_pass(std::string name, QueueType queue, std::function<void(PassBuilder&)> setup,
                     std::function<void(PassContext&)> execute) {
  const auto index = static_cast<uint32_t>(passes_.size());
  passes_.push_back(PassDecl{std::move(name), queue, {}, false, std::move(execute)});
  PassBuilder builder(*this, index);
  if (setup) setup(builder);
}

TextureHandle Graph::import_texture(std::string name, const TextureDesc& desc, ImportState initial,
                                    ImportState final_state, std::any physical) {
  uint32_t index = import_resource(std::move(name), ResourceKind::Texture, desc, {}, initial, final_state);
  resources_[index].physical = std::move(physical);
  return TextureHandle{index, 0, id_};
}

BufferHandle Graph::import_buffer(std::string name, const BufferDesc& desc, ImportState initial,
                                  ImportState final_state, std::any physical) {
  uint32_t index = import_resource(std::move(name), ResourceKind::Buffer, {}, desc, initial, final_state);
  resources_[index].physical = std::move(physical);
  return BufferHandle{index, 0, id_};
}

uint32_t Graph::import_resource(std::string name, ResourceKind kind, const TextureDesc& texture,
                                const BufferDesc& buffer, ImportState initial, ImportState final_state) {
  ResourceDecl resource;
  resource.name = std::move(name);
  resource.kind = kind;
  resource.texture = texture;
  resource.buffer = buffer;
  resource.imported = true;
  resource.initial = initial;
  resource.final_state = final_state;
  resource.writers = {kInvalidIndex};  // version 0 comes from outside the graph
  resources_.push_back(std::move(resource));
  last_access_.push_back({});
  return static_cast<uint32_t>(resources_.size() - 1);
}

void Graph::mark_output(TextureHandle texture) {
  mark_output(ResourceKind::Texture, texture.index, texture.version, texture.graph_id);
}

void Graph::mark_output(BufferHandle buffer) {
  mark_output(ResourceKind::Buffer, buffer.index, buffer.version, buffer.graph_id);
}

void Graph::mark_output(ResourceKind kind, uint32_t index, uint32_t version, uint32_t graph_id) {
  const ResourceDecl& resource = resolve(kInvalidIndex, kind, index, graph_id);
  check_version(kInvalidIndex, resource, version);
  outputs_.push_back(OutputDecl{index, version});
}

std::string Graph::who(uint32_t pass) const {
  return pass == kInvalidIndex ? std::string("mark_output") : "pass '" + passes_[pass].name + "'";
}

const ResourceDecl& Graph::resolve(uint32_t pass, ResourceKind kind, uint32_t index, uint32_t graph_id) const {
  if (graph_id == 0 || index == kInvalidIndex)
    throw GraphError(who(pass) + ": invalid (default-constructed) " + to_string(kind) + " handle");
  if (graph_id != id_)
    throw GraphError(who(pass) + ": handle to resource #" + std::to_string(index) +
                     " belongs to another graph (graph " + std::to_string(graph_id) + ", this is graph " +
                     std::to_string(id_) + ")");
  if (index >= resources_.size())
    throw GraphError(who(pass) + ": handle to unknown resource #" + std::to_string(index));
  const ResourceDecl& resource = resources_[index];
  if (resource.kind != kind)
    throw GraphError(who(pass) + ": '" + resource.name + "' is a " + to_string(resource.kind) + ", not a " +
                     to_string(kind));
  return resource;
}

void Graph::check_version(uint32_t pass, const ResourceDecl& resource, uint32_t version) const {
  const uint32_t current = resource.current_version();
  if (version == current) return;
  const char* what = version < current ? "stale" : "invalid";
  throw GraphError(who(pass) + ": " + what + " handle to '" + resource.name + "' (version " +
                   std::to_string(version) + ", current " + std::to_string(current) + ")");
}

// ---------------------------------------------------------------------------------------
// PassBuilder

TextureHandle PassBuilder::create_texture(std::string name, const TextureDesc& desc) {
  return TextureHandle{create(std::move(name), ResourceKind::Texture, desc, {}), 0, graph_.id_};
}

BufferHandle PassBuilder::create_buffer(std::string name, const BufferDesc& desc) {
  return BufferHandle{create(std::move(name), ResourceKind::Buffer, {}, desc), 0, graph_.id_};
}

uint32_t PassBuilder::create(std::string name, ResourceKind kind, const TextureDesc& texture,
                             const BufferDesc& buffer) {
  ResourceDecl resource;
  resource.name = std::move(name);
  resource.kind = kind;
  resource.texture = texture;
  resource.buffer = buffer;
  resource.created_by = pass_;
  resource.writers = {kInvalidIndex};  // version 0 of a transient has no contents yet
  graph_.resources_.push_back(std::move(resource));
  graph_.last_access_.push_back({});
  return static_cast<uint32_t>(graph_.resources_.size() - 1);
}

TextureHandle PassBuilder::read(TextureHandle t, Usage u) {
  return {t.index, access(ResourceKind::Texture, t.index, t.version, t.graph_id, u, true, false), t.graph_id};
}
BufferHandle PassBuilder::read(BufferHandle b, Usage u, BufferRange range) {
  return {b.index, access(ResourceKind::Buffer, b.index, b.version, b.graph_id, u, true, false, range), b.graph_id};
}
TextureHandle PassBuilder::write(TextureHandle t, Usage u) {
  return {t.index, access(ResourceKind::Texture, t.index, t.version, t.graph_id, u, false, true), t.graph_id};
}
BufferHandle PassBuilder::write(BufferHandle b, Usage u, BufferRange range) {
  return {b.index, access(ResourceKind::Buffer, b.index, b.version, b.graph_id, u, false, true, range), b.graph_id};
}
TextureHandle PassBuilder::read_write(TextureHandle t, Usage u) {
  return {t.index, access(ResourceKind::Texture, t.index, t.version, t.graph_id, u, true, true), t.graph_id};
}
BufferHandle PassBuilder::read_write(BufferHandle b, Usage u, BufferRange range) {
  return {b.index, access(ResourceKind::Buffer, b.index, b.version, b.graph_id, u, true, true, range), b.graph_id};
}

void PassBuilder::side_effect() { graph_.passes_[pass_].side_effect = true; }

BufferRange PassBuilder::checked_range(const ResourceDecl& resource, BufferRange range) const {
  if (range.whole()) return range;  // the buffer's own size is checked by the validate phase
  const uint64_t size = resource.buffer.size;
  if (range.size == kWholeSize && range.offset < size) range.size = size - range.offset;
  if (range.size == 0 || range.offset >= size || range.size > size - range.offset)
    throw GraphError(graph_.who(pass_) + ": range at " + std::to_string(range.offset) + " of " +
                     (range.size == kWholeSize ? std::string("all remaining") : std::to_string(range.size)) +
                     " bytes is empty or leaves buffer '" + resource.name + "' (" + std::to_string(size) +
                     " bytes)");
  return range.offset == 0 && range.size == size ? BufferRange{} : range;
}

uint32_t PassBuilder::access_slot(const ResourceDecl& resource, uint32_t index, BufferRange range) {
  PassDecl& pass = graph_.passes_[pass_];
  if (graph_.last_access_[index].pass == pass_) {
    const uint64_t size = resource.buffer.size;
    for (uint32_t slot = 0; slot < pass.accesses.size(); ++slot) {
      const AccessDecl& other = pass.accesses[slot];
      if (other.resource != index) continue;
      if (other.range == range) return slot;
      if (range.offset < other.range.end(size) && other.range.offset < range.end(size))
        throw GraphError(graph_.who(pass_) + ": uses overlapping ranges of '" + resource.name +
                         "'; one pass sees each byte in one state");
    }
  }
  pass.accesses.push_back(AccessDecl{index, range, {}, false, false, 0, 0});
  return static_cast<uint32_t>(pass.accesses.size() - 1);
}

// Records one read/write call and returns the handle's version afterwards. Repeated calls
// for the same resource (range) in one pass merge into one AccessDecl; a second write, or
// any use after the write, is refused (the pass would see its own output mid-pass).
uint32_t PassBuilder::access(ResourceKind kind, uint32_t index, uint32_t version, uint32_t graph_id, Usage usage,
                             bool reads, bool writes, BufferRange range) {
  const ResourceDecl& checked = graph_.resolve(pass_, kind, index, graph_id);
  PassDecl& pass = graph_.passes_[pass_];
  Graph::LastAccess& last = graph_.last_access_[index];
  const bool seen_in_this_pass = last.pass == pass_;
  if (seen_in_this_pass && pass.accesses[last.slot].writes)
    throw GraphError(graph_.who(pass_) + ": uses '" + checked.name +
                     "' again after writing it; a pass writes a resource once (use read_write())");
  graph_.check_version(pass_, checked, version);

  const bool usage_writes = usage_info(usage, pass.queue).is_write;
  if (usage_writes && !writes)
    throw GraphError(graph_.who(pass_) + ": read() of '" + checked.name + "' with usage " + to_string(usage) +
                     ", which writes; use write() or read_write()");
  if (!usage_writes && writes)
    throw GraphError(graph_.who(pass_) + ": write of '" + checked.name + "' with usage " + to_string(usage) +
                     ", which only reads; use read()");

  if (kind == ResourceKind::Buffer) range = checked_range(checked, range);
  last = Graph::LastAccess{pass_, access_slot(checked, index, range)};
  AccessDecl& decl = pass.accesses[last.slot];
  decl.usages.insert(usage);
  if (reads) {
    decl.reads = true;
    decl.read_version = version;
  }
  if (!writes) return version;

  ResourceDecl& resource = graph_.resources_[index];
  resource.writers.push_back(pass_);
  decl.writes = true;
  decl.written_version = resource.current_version();
  return decl.written_version;
}

}  // namespace rg
