#pragma once
// One frame's shadow work as plain data, for a host whose own frame graph schedules it
// (the way NVIDIA's NRD hands out its dispatches): an ordered list of passes, each with
// the resources it reads and writes and how (Vulkan stage, access and layout, from the
// frame graph's one usage table, rendergraph/src/usage_table.cpp), the transient
// resources the host allocates (and may alias), the persistent ones the engine owns
// (maps, parameter blocks, counters), and a function that records the pass into the
// host's command buffer on the physical resources the host resolved.
//
// Plain structs with Vulkan values and std::function only: no frame-graph type, so a
// host includes this without any rendergraph/ header. avsm::Shadows::pass_list() makes
// one (avsm/shadows.h); avsm::add_to_graph (avsm/shadows_rendergraph.h) declares it into
// the engine's own graph, which is how the engine's graph users run it too.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <functional>
#include <string>
#include <vector>

namespace avsm::passes {

inline constexpr uint32_t kNoPassResource = ~0u;

enum class PassQueue : uint8_t { graphics, compute, transfer };
const char* to_string(PassQueue queue);

// Stages and accesses that last touched a resource (or will touch it next) and, for an
// image, its layout: a persistent resource's state before and after the frame.
struct PassResourceState {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;
};

// A resource of the frame. Transient ones the host creates for the frame from `image` or
// `buffer` (their usage flags cover every use in the list) and may alias with others whose
// lifetimes do not overlap: their first use writes them, nothing is kept from before.
// Persistent ones are the engine's: `handle` and `offset` locate their bytes, and the
// frame takes them from `initial` and leaves them in `final_state`.
struct PassResource {
  enum class Kind : uint8_t { image, buffer };

  std::string name;  // unique in the list ("light 0 capture nodes")
  Kind kind = Kind::buffer;
  bool transient = true;
  struct Image {
    uint32_t width = 0, height = 0, depth = 1, mip_levels = 1, array_layers = 1;
    VkFormat format = VK_FORMAT_UNDEFINED;
    VkImageUsageFlags usage = 0;
  } image;  // kind image
  struct Buffer {
    VkDeviceSize size = 0;
    VkBufferUsageFlags usage = 0;
  } buffer;  // kind buffer
  std::string sized_by;  // the setting that sizes it, to name when the device cannot hold it

  // Persistent buffers only: bytes [offset, offset + buffer.size) of `handle`.
  VkBuffer handle = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  PassResourceState initial, final_state;
};

// How one pass uses one resource (or, for a buffer, a byte range of it).
struct PassResourceUse {
  uint32_t resource = kNoPassResource;  // index into ShadowPassList::resources
  VkDeviceSize offset = 0;              // buffers: bytes [offset, offset + size) of the resource
  VkDeviceSize size = VK_WHOLE_SIZE;    // VK_WHOLE_SIZE: to its end
  bool reads = false;   // depends on what earlier passes (or frames) left in it
  bool writes = false;  // changes it
  std::vector<std::string> usages;  // the usage table's names: "StorageReadWrite", "TransferSrc", ...
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // images: what the pass needs it in
};

// What the host's graph resolved a resource to for one pass. Transients: a buffer's
// VkBuffer and where the resource starts in it; an image and a view of all its mips and
// layers, in the use's layout. Persistent resources may be left empty (the pass uses the
// list's own handle); given, they must be that handle.
struct ResolvedResource {
  VkBuffer buffer = VK_NULL_HANDLE;
  VkDeviceSize offset = 0;
  VkImage image = VK_NULL_HANDLE;
  VkImageView view = VK_NULL_HANDLE;
};

struct ShadowPass {
  std::string name;  // unique in the list ("light 0 capture opaque")
  PassQueue queue = PassQueue::graphics;
  std::vector<PassResourceUse> uses;
  bool side_effect = false;  // has effects outside the listed resources: never cull it
  // Records the pass into `cmd`, inside whatever barriers the host placed: `resources`
  // holds one entry per list resource (by index; only this pass's are looked at). Throws
  // std::invalid_argument naming the pass and resource for a missing or wrong one.
  std::function<void(VkCommandBuffer cmd, const std::vector<ResolvedResource>& resources)> record;
};

// A bound range of one of the engine's buffers.
struct PassBufferRange {
  VkBuffer buffer = VK_NULL_HANDLE;  // VK_NULL_HANDLE: none (bind `unused_buffer` there)
  VkDeviceSize offset = 0;
  VkDeviceSize size = VK_WHOLE_SIZE;
};

// What the host's shading passes read to look the shadows up
// (shaders/common/shadow_lookup.glsl): the list resources to declare as storage reads
// after the list's passes, and the buffers to bind whole.
struct ShadowLookupResources {
  uint32_t records = kNoPassResource;  // the frame's GpuShadow records; kNoPassResource: static
  std::vector<uint32_t> maps;          // every map the frame builds (regions of `atlas`)
  std::vector<uint32_t> lists;         // the looked-up capture lists (regions of list_heads/nodes)
  PassBufferRange parameters, atlas, list_heads, list_nodes;
  // Paged maps' request bits, cleared by the frame, which the lookups that ask for pages
  // write (shaders/common/shadow_lookup.glsl, AVSM_SHADOW_PAGE_REQUESTS_BINDING) and
  // finish_frame() reads; kNoPassResource and no buffer without paged maps.
  uint32_t page_requests = kNoPassResource;
  PassBufferRange page_request_bits;
  VkBuffer unused_buffer = VK_NULL_HANDLE;  // bound where there is no atlas, no lists or no page requests
  uint32_t frame_slot = 0;
};

// What the host's shading binds to composite the engine's fog (shaders/common/fog.glsl:
// AVSM_FOG_BINDING, AVSM_FOG_INTEGRATED_BINDING, then fog_towards(pixel, distance)): the
// frame's fog parameters and its integrated grid, both storage buffers. `integrated` is
// the list resource the fog passes write (declare it as a storage read after them);
// kNoPassResource when the frame has no fog, and `grid` is then `parameters` again, bound
// but unread (the header says there is no fog).
struct FogLookupResources {
  uint32_t integrated = kNoPassResource;
  PassBufferRange parameters, grid;
};

// One frame's shadow work. Run the passes in list order (each pass's reads see the
// writes of the passes before it, as the uses say); the list is valid until the frame
// slot's finish_frame() (or new lights). Caster buffers are not listed: they are read as
// static data, uploaded before the frame and unchanged until it completes.
struct ShadowPassList {
  std::vector<PassResource> resources;
  std::vector<ShadowPass> passes;
  ShadowLookupResources lookup;
  FogLookupResources fog;  // with Shadows::set_fog; the fog passes end the list
};

}  // namespace avsm::passes
