#pragma once
// A light's capture lists in the frame graph: the head-pointer image (one list
// per light texel), the node buffer every capture pass appends segments to, and
// the persistent counter the CPU reads after the frame to see how many nodes were
// asked for (shaders/common/capture_lists.glsl). Heads and nodes are transient:
// the graph places them in its heaps, and one light's lists alias the previous
// light's once that light is resolved.
#include <rendergraph/graph.h>

#include <cstdint>
#include <string>

#include "passes/shadows/light_view.h"
#include "shared/capture.h"

namespace avsm::gpu {
class Bindings;
}

namespace avsm::passes {

inline constexpr uint64_t kCaptureSegmentBytes = sizeof(shared::CaptureSegment);
inline constexpr VkFormat kCaptureHeadFormat = VK_FORMAT_R32_UINT;

struct CaptureLists {
  rg::TextureHandle heads;   // R32_UINT, resolution x resolution
  rg::BufferHandle nodes;    // node_capacity CaptureSegments
  rg::BufferHandle counter;  // uint 0: nodes asked for, including those that did not fit; uint 1: deep
                             // shadow map pool nodes asked for, uint 2: its build dispatches needed
                             // (dsm_build.comp); 16 bytes, cleared
};

// Declares "<prefix> clear lists": creates the heads and nodes, clears every head
// to the end-of-list value and the counter to 0. `counter` is an imported buffer
// of 16 bytes (cleared whole).
CaptureLists add_capture_clear_pass(rg::Graph& graph, const std::string& prefix, uint32_t resolution,
                                    uint64_t node_capacity, rg::BufferHandle counter);

// For a pass that appends: declares read-write access to all three and returns
// the new versions.
CaptureLists append_to_lists(rg::PassBuilder& builder, const CaptureLists& lists);

// Begins rendering a light's map (no attachments: the captures append to the lists)
// with the viewport of its whole raster and the render area of the map's window in it:
// a page of a paged map rasterizes exactly as its raster would, and the captures append
// at gl_FragCoord - LightView::raster_origin.
void begin_light_rendering(VkCommandBuffer cmd, const LightView& view);

// Binds heads, nodes and counter by their shader names (shaders/common/capture_lists.glsl).
void bind_capture_lists(gpu::Bindings& bindings, const rg::PassContext& context,
                        const CaptureLists& lists);

}  // namespace avsm::passes
