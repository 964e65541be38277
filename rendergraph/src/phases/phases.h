#pragma once
// The compiler is a fixed list of phases over one CompileState; each phase lives in its
// own file, reads what earlier phases produced and fills in its own part:
//
//   validate     the declaration is well-formed (throws GraphError)
//   cull         which passes contribute to something observable      -> kept
//   order        execution order of the kept passes                    -> order, position
//   lifetimes    first/last position and usage union per resource      -> lifetimes
//   memory plan  heaps and offsets for transients, aliasing            -> placements, heaps
//   barrier plan barriers before each pass and after the last          -> barriers, final_barriers
//   build plan   the CompiledPlan handed to the executor
#include <rendergraph/graph.h>

#include <cstdint>
#include <vector>

namespace rg::detail {

// What one access needs from the hardware: the usage table applied to all its usages.
struct AccessNeeds {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // textures only
  bool writes = false;
};
AccessNeeds access_needs(const AccessDecl& access, QueueType queue, ResourceKind kind);

struct Lifetime {
  bool used = false;
  uint32_t first = kInvalidIndex;  // positions in execution order
  uint32_t last = kInvalidIndex;
  UsageSet usages;
};

struct Placement {
  MemoryRequirements requirements;
  uint32_t heap = kInvalidIndex;
  uint64_t offset = 0;
  // Bytes the resource blocks in its heap: its size, rounded up to bufferImageGranularity
  // for images so that no buffer shares a granularity page with an image.
  uint64_t footprint = 0;
};

struct CompileState {
  CompileState(const Graph& g, const MemoryModel& m, const CompileOptions& o) : graph(g), memory(m), options(o) {}

  const Graph& graph;
  const MemoryModel& memory;
  CompileOptions options;

  std::vector<bool> kept;             // cull: per declared pass
  std::vector<uint32_t> order;        // order: declared pass index per position
  std::vector<uint32_t> position;     // order: position per declared pass (kInvalidIndex if culled)
  std::vector<Lifetime> lifetimes;    // lifetimes: per resource
  std::vector<Placement> placements;  // memory plan: per resource (transients only)
  std::vector<PlannedHeap> heaps;     // memory plan
  std::vector<std::vector<Barrier>> barriers;  // barrier plan: per position
  std::vector<Barrier> final_barriers;         // barrier plan
};

void validate(const Graph& graph);
void cull(CompileState& state);
void order_passes(CompileState& state);
void compute_lifetimes(CompileState& state);
void plan_memory(CompileState& state);
void plan_barriers(CompileState& state);
CompiledPlan build_plan(CompileState& state);

}  // namespace rg::detail
