#pragma once
// An independent checker for compiled plans. It shares no code with the planner: it
// re-derives lifetimes, usages, producers and hazards from the Graph declaration and the
// plan's pass order, with its own small table of what each usage needs, and then checks
//
//   structure  every declared pass is either planned or culled; anchors (side effects,
//              writes to imports, outputs) are kept; with culling on nothing else is;
//              every read follows its producer (or an import) and precedes the next write
//   memory     used transients are placed in a heap of compatible memory type, aligned,
//              inside the heap; no two placements in one heap overlap (images rounded out
//              to bufferImageGranularity pages) while their lifetimes overlap, or at all
//              with aliasing off
//   hazards    per resource (per byte interval of a buffer: the resource is cut wherever an
//              access or barrier range starts or ends, and each interval is checked against
//              the accesses and barriers covering it), in execution order: every RAW/WAW is covered by a barrier
//              after the earlier access whose src covers its stages and write accesses and
//              whose dst covers the later stages and accesses; every WAR by one whose src
//              covers the reader's stages; layout transitions count as writes; a
//              transient's first use is covered against the last accesses of the resources
//              that last occupied its memory
//   layouts    every access sees the layout its usage needs; no transition discards live
//              contents; imported resources end in their final state
//
// It is deliberately stricter than Vulkan in one way: the src of a covering barrier must
// name the earlier access directly (only layout transitions and imported read states may
// be reached through an execution dependency chain).
#include <rendergraph/graph.h>

#include <string>
#include <vector>

namespace rg_test {

// One message per problem; empty means the plan is valid for this graph.
std::vector<std::string> verify_plan(const rg::Graph& graph, const rg::CompiledPlan& plan,
                                     const rg::MemoryModel& memory);

}  // namespace rg_test
