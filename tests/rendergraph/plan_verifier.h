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

#include <cstdint>
#include <optional>
#include <string>
#include <vector>

namespace rg_test {

// One message per problem; empty means the plan is valid for this graph.
std::vector<std::string> verify_plan(const rg::Graph& graph, const rg::CompiledPlan& plan,
                                     const rg::MemoryModel& memory);

// Persistent state: what frames leave in the memory they import for the frames after.
// The graph sees one frame; an import's initial state is the frame's claim about what the
// frames before it left. Only the memory behind the imports can say whether that claim
// holds, so the caller names it, while the frame's resources still live: `object` is the
// buffer or image (its handle), [begin, end) the bytes an import covers ({0, 1} for an
// image).
struct PhysicalRange {
  uint64_t object = 0;
  uint64_t begin = 0, end = 0;
};

struct PlannedFrame {
  const rg::Graph* graph = nullptr;
  const rg::CompiledPlan* plan = nullptr;
  std::vector<std::optional<PhysicalRange>> memory;  // per resource: an import's memory; nullopt leaves it out
  // Frames [0, completed_before) had completed (the host waited for their fences) when
  // this one was submitted: what they left is drained, but for images' layouts.
  size_t completed_before = 0;
};

// Checks frames submitted one after another to one queue: each with verify_plan, and
//   overlap   within a frame, where two imports' memory overlaps, every access to one that
//             conflicts with an access to the other (either writes) is ordered after it by
//             a barrier on either, as if they were one resource; a pass that writes one
//             while it uses the other cannot be ordered at all
//   carried   across frames, every import's initial state is true of what the last frame
//             to use that memory left there: an image is in the layout it was left in (or
//             UNDEFINED, discarding it); unless that frame had completed, accesses it left
//             open (final state none) are inside the initial state's stages, their writes
//             in its accesses, so the frame's first barriers wait for them, and where it
//             left a final state, the initial state claims no stage or access it did not
//             make visible, and chains to it through a shared stage. A final state in HOST
//             stages only is drained: the host waits for the frame before reading.
// Messages start with "frame <i>: ".
std::vector<std::string> verify_frames(const std::vector<PlannedFrame>& frames, const rg::MemoryModel& memory);

}  // namespace rg_test
