#pragma once
// Small hand-written graphs shared by the golden, verifier and plan tests.
#include <rendergraph/graph.h>

namespace rg_test {

// Execute callbacks in core tests never run: the core only stores them.
inline void no_execute(rg::PassContext&) {}

rg::TextureDesc texture_desc(uint32_t width, uint32_t height, VkFormat format);

rg::Graph diamond_graph();        // gbuffer -> (ssao, direct light) -> combine -> backbuffer
rg::Graph culled_branch_graph();  // a debug branch nobody reads is culled; output/side effect kept
rg::Graph multi_light_graph(int lights = 3);  // per-light capture/sort/resolve, transients alias
rg::Graph buffer_raw_graph();     // upload -> GPU culling -> indirect draw -> stats readback
rg::Graph history_graph();        // TAA history read from last frame and written for the next
rg::Graph mip_chain_graph();      // a map's levels in ranges of one buffer, each built from the one above

}  // namespace rg_test
