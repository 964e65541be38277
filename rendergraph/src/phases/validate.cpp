// Phase 1: validate. Checks the declaration as a whole; handle misuse (stale, foreign)
// was already refused by PassBuilder at the call. Throws GraphError naming pass/resource.
#include <string>
#include <string_view>
#include <unordered_map>

#include "phases.h"

namespace rg::detail {
namespace {

std::string quoted(const std::string& name) { return "'" + name + "'"; }

void check_unique_pass_names(const Graph& graph) {
  std::unordered_map<std::string_view, size_t> seen;
  for (size_t i = 0; i < graph.passes().size(); ++i) {
    const std::string& name = graph.passes()[i].name;
    if (name.empty()) throw GraphError("pass #" + std::to_string(i) + " has an empty name");
    auto [it, inserted] = seen.emplace(name, i);
    if (!inserted)
      throw GraphError("duplicate pass name " + quoted(name) + " (passes #" + std::to_string(it->second) +
                       " and #" + std::to_string(i) + ")");
  }
}

// Names identify resources in messages, dumps and debug labels: they must be unique.
void check_unique_resource_names(const Graph& graph) {
  auto origin = [&](const ResourceDecl& r) {
    return r.imported ? std::string("imported") : "created by pass " + quoted(graph.passes()[r.created_by].name);
  };
  std::unordered_map<std::string_view, size_t> seen;
  for (size_t i = 0; i < graph.resources().size(); ++i) {
    const ResourceDecl& resource = graph.resources()[i];
    if (resource.name.empty()) throw GraphError("resource #" + std::to_string(i) + " has an empty name");
    auto [it, inserted] = seen.emplace(resource.name, i);
    if (!inserted)
      throw GraphError("duplicate resource name " + quoted(resource.name) + " (" +
                       origin(graph.resources()[it->second]) + ", and " + origin(resource) + ")");
  }
}

void check_desc(const ResourceDecl& r) {
  if (r.kind == ResourceKind::Buffer) {
    if (r.buffer.size == 0) throw GraphError("buffer " + quoted(r.name) + " has size 0");
    return;
  }
  const TextureDesc& d = r.texture;
  if (d.width == 0 || d.height == 0 || d.depth == 0 || d.mip_levels == 0 || d.array_layers == 0)
    throw GraphError("texture " + quoted(r.name) + " has a zero extent, mip count or layer count");
  if (d.format == VK_FORMAT_UNDEFINED) throw GraphError("texture " + quoted(r.name) + " has no format");
}

void check_access(const Graph& graph, const PassDecl& pass, const AccessDecl& access) {
  const ResourceDecl& resource = graph.resources()[access.resource];
  const std::string where = "pass " + quoted(pass.name) + ": " + quoted(resource.name);

  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
  access.usages.for_each([&](Usage usage) {
    if (const char* problem = usage_problem(usage, pass.queue, resource.kind))
      throw GraphError(where + ": usage " + to_string(usage) + " " + problem);
    if (resource.kind != ResourceKind::Texture) return;
    // One access is one layout: e.g. Sampled + StorageWrite in one pass cannot work.
    const VkImageLayout needed = usage_info(usage, pass.queue).layout;
    if (layout != VK_IMAGE_LAYOUT_UNDEFINED && needed != layout)
      throw GraphError(where + ": usages need different layouts in the same pass");
    layout = needed;
  });

  if (!access.reads || access.read_version != 0) return;
  if (!resource.imported)
    throw GraphError(where + ": read before any pass wrote it");
  if (resource.kind == ResourceKind::Texture && resource.initial.layout == VK_IMAGE_LAYOUT_UNDEFINED)
    throw GraphError(where + ": read, but the imported contents are undefined (initial layout UNDEFINED)");
}

void check_outputs(const Graph& graph) {
  for (const OutputDecl& output : graph.outputs()) {
    const ResourceDecl& resource = graph.resources()[output.resource];
    if (!resource.imported && output.version == 0)
      throw GraphError("mark_output: " + quoted(resource.name) + " was never written");
  }
}

}  // namespace

void validate(const Graph& graph) {
  check_unique_pass_names(graph);
  check_unique_resource_names(graph);
  for (const ResourceDecl& resource : graph.resources()) check_desc(resource);
  for (const PassDecl& pass : graph.passes())
    for (const AccessDecl& access : pass.accesses) check_access(graph, pass, access);
  check_outputs(graph);
}

}  // namespace rg::detail
