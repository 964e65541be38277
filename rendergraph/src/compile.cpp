// Graph::compile: the phases, in order. See phases/phases.h for what each one does.
#include <rendergraph/graph.h>

#include "phases/phases.h"

namespace rg {

CompiledPlan Graph::compile(const MemoryModel& memory, const CompileOptions& options) const {
  detail::validate(*this);
  detail::CompileState state(*this, memory, options);
  detail::cull(state);
  detail::order_passes(state);
  detail::compute_lifetimes(state);
  detail::plan_memory(state);
  detail::plan_barriers(state);
  return detail::build_plan(state);
}

namespace detail {

AccessNeeds access_needs(const AccessDecl& access, QueueType queue, ResourceKind kind) {
  AccessNeeds needs;
  access.usages.for_each([&](Usage usage) {
    const UsageInfo info = usage_info(usage, queue);
    needs.stages |= info.stages;
    needs.access |= info.access;
    needs.writes |= info.is_write;
    if (kind == ResourceKind::Texture) needs.layout = info.layout;  // validate: all usages agree
  });
  return needs;
}

}  // namespace detail
}  // namespace rg
