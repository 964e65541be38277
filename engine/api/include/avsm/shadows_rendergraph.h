#pragma once
// The engine's shadows in a host that adopts the engine's own frame graph (rendergraph/):
// the frame's pass list (avsm/shadows.h) declared as graph passes, and what the host's
// shading passes declare and bind to read the maps.
//
//   rg::Graph graph;
//   avsm::ShadowInputs maps = avsm::add_to_graph(graph, shadows, camera, casters);
//   graph.add_pass<...>("my shading", ...,
//       [&](rg::PassBuilder& b, ...) { maps.declare_reads(b); ... },
//       [=](..., rg::PassContext& c) { avsm::gpu::Bindings bindings(context, pipeline);
//                                      maps.bind(bindings, c); ... });   // binds by name
//   executor.record(graph, cmd); submit, wait;
//   shadows.finish_frame();
//
// Bindings go through push descriptors (VK_KHR_push_descriptor, avsm::gpu::Pipeline /
// Bindings, by the shader's names); ShadowInputs' fields hold the raw handles too.
#include <rendergraph/graph.h>

#include <cstdint>

#include "avsm/shadows.h"
#include "passes/shadows/shadow_inputs.h"

namespace avsm {

using passes::ShadowInputs;

// Declares every pass of `list` into `graph`, in list order, with the uses the list gives
// (transients created by the pass that first uses them, persistent resources imported
// with their handles, so any executor can run it); each pass records through the list's
// record function. Returns what the host's shading passes declare as reads and bind
// (with the fog: its grid among the reads, and bind_fog for the composite).
ShadowInputs add_to_graph(rg::Graph& graph, const ShadowPassList& list);

// shadows.pass_list(camera, casters, frame_slot) declared into `graph` (its preconditions
// and exceptions).
ShadowInputs add_to_graph(rg::Graph& graph, Shadows& shadows, const Camera& camera, const ShadowCasters& casters,
                          uint32_t frame_slot = 0);

// Inputs that leave every light unshadowed (shadows.unshadowed_lookup()), for a pass drawn
// without maps.
ShadowInputs unshadowed_inputs(const Shadows& shadows);

}  // namespace avsm
