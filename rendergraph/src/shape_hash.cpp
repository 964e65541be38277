// Graph::shape_hash: everything the plan depends on, hashed with a stable hash, so an
// executor can tell "same frame shape as last time" and reuse its compiled plan.
#include <rendergraph/graph.h>

#include "hash.h"

namespace rg {
namespace {

void add_state(detail::Fnv1a& hash, const ImportState& state) {
  hash.add(state.stages);
  hash.add(state.access);
  hash.add(static_cast<uint64_t>(state.layout));
}

}  // namespace

uint64_t Graph::shape_hash(const CompileOptions& options) const {
  detail::Fnv1a hash;
  hash.add(uint64_t{options.aliasing} | uint64_t{options.culling} << 1 | uint64_t{options.serial_full_barriers} << 2);

  hash.add(resources_.size());
  for (const ResourceDecl& resource : resources_) {
    hash.add(resource.name);
    hash.add(static_cast<uint64_t>(resource.kind));
    hash.add(resource.kind == ResourceKind::Texture ? hash_value(resource.texture) : hash_value(resource.buffer));
    hash.add(uint64_t{resource.imported});
    add_state(hash, resource.initial);
    add_state(hash, resource.final_state);
  }

  hash.add(passes_.size());
  for (const PassDecl& pass : passes_) {
    hash.add(pass.name);
    hash.add(static_cast<uint64_t>(pass.queue));
    hash.add(uint64_t{pass.side_effect});
    hash.add(pass.accesses.size());
    for (const AccessDecl& access : pass.accesses) {
      hash.add(access.resource);
      hash.add(access.range.offset);
      hash.add(access.range.size);
      hash.add(access.usages.bits());
      hash.add(uint64_t{access.reads} | uint64_t{access.writes} << 1);
      hash.add(access.read_version);
      hash.add(access.written_version);
    }
  }

  hash.add(outputs_.size());
  for (const OutputDecl& output : outputs_) {
    hash.add(output.resource);
    hash.add(output.version);
  }
  return hash.value();
}

}  // namespace rg
