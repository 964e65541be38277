// Phase 7: the plan. Gathers what the earlier phases decided into the CompiledPlan the
// executor consumes; no decisions are made here.
#include "phases.h"

namespace rg::detail {
namespace {

PlannedPass planned_pass(const Graph& graph, uint32_t pass_index) {
  const PassDecl& decl = graph.passes()[pass_index];
  PlannedPass pass;
  pass.name = decl.name;
  pass.queue = decl.queue;
  pass.pass_index = pass_index;
  pass.accesses.reserve(decl.accesses.size());
  for (const AccessDecl& access : decl.accesses) {
    const AccessNeeds needs = access_needs(access, decl.queue, graph.resources()[access.resource].kind);
    pass.accesses.push_back(PlannedAccess{access.resource, access.range, access.usages, access.reads, access.writes,
                                          access.read_version, access.written_version, needs.stages,
                                          needs.access, needs.layout});
  }
  return pass;
}

PlannedResource planned_resource(const ResourceDecl& decl, const Lifetime& life, const Placement& placement) {
  PlannedResource resource;
  resource.name = decl.name;
  resource.kind = decl.kind;
  resource.texture = decl.texture;
  resource.buffer = decl.buffer;
  resource.imported = decl.imported;
  resource.initial = decl.initial;
  resource.final_state = decl.final_state;
  resource.used = life.used;
  resource.first_pass = life.first;
  resource.last_pass = life.last;
  resource.usages = life.usages;
  if (decl.kind == ResourceKind::Texture) {
    resource.image_usage = image_usage_flags(life.usages);
    resource.aspect = aspect_flags(decl.texture.format);
  } else {
    resource.buffer_usage = buffer_usage_flags(life.usages);
  }
  resource.heap = placement.heap;
  resource.offset = placement.offset;
  resource.size = placement.requirements.size;
  resource.alignment = placement.requirements.alignment;
  return resource;
}

}  // namespace

CompiledPlan build_plan(CompileState& state) {
  const Graph& graph = state.graph;
  CompiledPlan plan;
  plan.options = state.options;
  plan.shape_hash = graph.shape_hash(state.options);

  plan.passes.reserve(state.order.size());
  for (uint32_t position = 0; position < state.order.size(); ++position) {
    plan.passes.push_back(planned_pass(graph, state.order[position]));
    plan.passes.back().barriers = std::move(state.barriers[position]);
    plan.stats.barrier_count += static_cast<uint32_t>(plan.passes.back().barriers.size());
  }
  for (uint32_t pass = 0; pass < graph.passes().size(); ++pass)
    if (!state.kept[pass]) plan.culled_passes.push_back(planned_pass(graph, pass));
  plan.final_barriers = std::move(state.final_barriers);
  plan.stats.barrier_count += static_cast<uint32_t>(plan.final_barriers.size());

  plan.resources.reserve(graph.resources().size());
  for (uint32_t r = 0; r < graph.resources().size(); ++r) {
    plan.resources.push_back(planned_resource(graph.resources()[r], state.lifetimes[r], state.placements[r]));
    if (plan.resources.back().heap != kInvalidIndex) plan.stats.transient_bytes_unaliased += plan.resources.back().size;
  }
  plan.heaps = std::move(state.heaps);
  for (const PlannedHeap& heap : plan.heaps) plan.stats.transient_bytes_aliased += heap.size;
  return plan;
}

}  // namespace rg::detail
