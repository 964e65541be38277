// Phase 3: order. Kept passes run in declaration order. Setup runs inside add_pass, so a
// pass can only read versions produced by passes declared before it: declaration order
// is already a valid topological order, and keeping it makes plans predictable (the
// author decides, e.g., where a long-running compute pass sits).
#include "phases.h"

namespace rg::detail {

void order_passes(CompileState& state) {
  const size_t pass_count = state.graph.passes().size();
  state.position.assign(pass_count, kInvalidIndex);
  state.order.clear();
  for (uint32_t pass = 0; pass < pass_count; ++pass) {
    if (!state.kept[pass]) continue;
    state.position[pass] = static_cast<uint32_t>(state.order.size());
    state.order.push_back(pass);
  }
}

}  // namespace rg::detail
