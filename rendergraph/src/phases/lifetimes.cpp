// Phase 4: lifetimes. For every resource, the first and last position that touches it and
// every usage it sees in kept passes (this decides its creation flags, hence its memory
// requirements). Outputs stay alive until the end so their contents survive the graph.
#include <algorithm>

#include "phases.h"

namespace rg::detail {

void compute_lifetimes(CompileState& state) {
  const auto& passes = state.graph.passes();
  state.lifetimes.assign(state.graph.resources().size(), Lifetime{});

  for (uint32_t position = 0; position < state.order.size(); ++position) {
    for (const AccessDecl& access : passes[state.order[position]].accesses) {
      Lifetime& life = state.lifetimes[access.resource];
      if (!life.used) life.first = position;  // positions only grow: first touch is first
      life.used = true;
      life.last = position;
      life.usages.insert(access.usages);
    }
  }

  if (state.order.empty()) return;
  const auto last_position = static_cast<uint32_t>(state.order.size()) - 1;
  for (const OutputDecl& output : state.graph.outputs()) {
    Lifetime& life = state.lifetimes[output.resource];
    if (life.used) life.last = last_position;
  }
}

}  // namespace rg::detail
