// Phase 2: cull. A pass is kept when something observable depends on it: it has a side
// effect, it writes an imported resource (visible after the graph), it produced a version
// marked as output, or a kept pass reads a version it produced. Reverse reachability
// from those anchors, O(passes + accesses). A write of a buffer range keeps the rest of the
// buffer, so its pass depends on the producer of the version it replaced.
#include "phases.h"

namespace rg::detail {

void cull(CompileState& state) {
  const auto& passes = state.graph.passes();
  const auto& resources = state.graph.resources();
  state.kept.assign(passes.size(), !state.options.culling);
  if (!state.options.culling) return;

  std::vector<uint32_t> pending;
  auto keep = [&](uint32_t pass) {
    if (pass == kInvalidIndex || state.kept[pass]) return;  // kInvalidIndex: imported contents
    state.kept[pass] = true;
    pending.push_back(pass);
  };

  for (uint32_t p = 0; p < passes.size(); ++p) {
    if (passes[p].side_effect) keep(p);
    for (const AccessDecl& access : passes[p].accesses)
      if (access.writes && resources[access.resource].imported) keep(p);
  }
  for (const OutputDecl& output : state.graph.outputs()) keep(resources[output.resource].writers[output.version]);

  while (!pending.empty()) {
    const uint32_t pass = pending.back();
    pending.pop_back();
    for (const AccessDecl& access : passes[pass].accesses) {
      const std::vector<uint32_t>& writers = resources[access.resource].writers;
      if (access.reads) keep(writers[access.read_version]);
      if (access.writes && !access.range.whole()) keep(writers[access.written_version - 1]);
    }
  }
}

}  // namespace rg::detail
