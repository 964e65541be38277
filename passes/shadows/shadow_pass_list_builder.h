#pragma once
// Makes the shadow pass list (passes/shadows/shadow_pass_list.h) from the frame-graph
// declarations the passes already make: the frame is declared into a graph of its own,
// whose passes, resources and accesses become plain data, the usages turned into Vulkan
// terms by the graph's usage table. Each pass's record function runs the declared
// execute step on the resources the host resolved. So there is one description of every
// pass: its add_to_graph.
#include <rendergraph/graph.h>

#include <cstdint>

#include "passes/shadows/shadow_casters.h"
#include "passes/shadows/shadow_inputs.h"
#include "passes/shadows/shadow_pass_list.h"
#include "passes/frame/view.h"

namespace avsm::gpu {
class Context;
}

namespace avsm::passes {

class ShadowMaps;
struct FogInputs;  // passes/camera/fog/fog_media.h

// The passes and resources of `graph`, in declaration order (list index = graph index).
// Imported resources must be buffers carrying their gpu::Buffer (rg::vulkan::import).
// `ctx` is what the record functions record with; it must outlive the list (nullptr: a
// list to look at only, whose record functions throw std::logic_error).
ShadowPassList pass_list_of(const rg::Graph& graph, const gpu::Context* ctx);

// What the shading reads, by the indices of the graph the inputs were declared in.
ShadowLookupResources lookup_of(const ShadowInputs& inputs);
// What a host's composite of the fog binds (passes/camera/fog/fog_media.h), likewise.
FogLookupResources fog_lookup_of(const FogInputs& inputs);

// This frame's shadow work of `maps` into frame slot `slot`, as ShadowMaps::add_to_graph
// declares it (and with its preconditions).
ShadowPassList describe_shadow_frame(ShadowMaps& maps, const gpu::Context& ctx, const View& camera,
                                     const ShadowCasters& casters, uint32_t slot = 0);

}  // namespace avsm::passes
