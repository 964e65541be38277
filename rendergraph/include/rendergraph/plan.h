#pragma once
// The result of Graph::compile(): everything a Vulkan executor needs to run one frame,
// with no further decisions left to make.
//
// Queues: every pass records its QueueType (timing tracks, a future async-compute
// executor), but barriers are planned as if ALL passes run in plan order on ONE queue.
// An executor that submits compute passes to another queue must add queue-ownership
// transfers and semaphores itself; this plan does not contain them.
#include <rendergraph/memory_model.h>
#include <rendergraph/usage.h>

#include <string>
#include <vector>

namespace rg {

struct CompileOptions {
  bool aliasing = true;               // off: every transient gets its own memory range
  bool culling = true;                // off: keep passes whose results nobody uses
  bool serial_full_barriers = false;  // on: ALL_COMMANDS/MEMORY_READ|WRITE barrier between passes
                                      // (in addition to the normal barriers and layout changes)
  bool operator==(const CompileOptions&) const = default;
};

// A sync2-shaped barrier over a whole resource (all mips/layers, or the whole buffer) or a
// range of a buffer. resource == kInvalidIndex means a global VkMemoryBarrier2 (serial
// mode only).
struct Barrier {
  uint32_t resource = kInvalidIndex;  // index into CompiledPlan::resources
  BufferRange range;                  // buffers: the bytes it covers (offset/size as in Vulkan)
  VkPipelineStageFlags2 src_stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 src_access = VK_ACCESS_2_NONE;
  VkPipelineStageFlags2 dst_stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 dst_access = VK_ACCESS_2_NONE;
  VkImageLayout old_layout = VK_IMAGE_LAYOUT_UNDEFINED;  // textures only
  VkImageLayout new_layout = VK_IMAGE_LAYOUT_UNDEFINED;  // textures only
  // First use of memory that earlier resources occupied: the src side covers their last
  // accesses and a texture starts from UNDEFINED. Lists those earlier resources.
  std::vector<uint32_t> aliased;

  bool is_global() const { return resource == kInvalidIndex; }
  bool operator==(const Barrier&) const = default;
};

// One access of a pass, with the usage table already applied (descriptor layouts,
// attachment layouts and pipeline stages for the executor).
struct PlannedAccess {
  uint32_t resource = kInvalidIndex;
  BufferRange range;  // buffers: the bytes this access touches
  UsageSet usages;
  bool reads = false;   // consumes the previous version
  bool writes = false;  // produces a new version
  uint32_t read_version = 0;
  uint32_t written_version = 0;
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // textures only
};

struct PlannedPass {
  std::string name;
  QueueType queue = QueueType::Graphics;
  uint32_t pass_index = kInvalidIndex;  // into Graph::passes(): whose execute to call
  std::vector<Barrier> barriers;        // record all of these before the pass
  std::vector<PlannedAccess> accesses;
};

struct PlannedResource {
  std::string name;
  ResourceKind kind = ResourceKind::Texture;
  TextureDesc texture;  // kind == Texture
  BufferDesc buffer;    // kind == Buffer
  bool imported = false;
  ImportState initial;      // imported only
  ImportState final_state;  // imported only
  bool used = false;        // some kept pass accesses it; unused transients get no memory
  uint32_t first_pass = kInvalidIndex;  // positions in CompiledPlan::passes (lifetime)
  uint32_t last_pass = kInvalidIndex;
  UsageSet usages;                    // union over kept passes
  VkImageUsageFlags image_usage = 0;  // image_usage_flags(usages), textures
  VkBufferUsageFlags buffer_usage = 0;
  VkImageAspectFlags aspect = 0;  // for whole-image barriers, textures
  // Placement of a used transient; heap == kInvalidIndex for imported/unused ones.
  uint32_t heap = kInvalidIndex;
  uint64_t offset = 0;
  uint64_t size = 0;  // MemoryRequirements::size from the model
  uint64_t alignment = 0;
};

// One VkDeviceMemory (or VMA block) the executor allocates; transients are bound at
// their offsets. Every resident accepts every type in memory_type_bits.
struct PlannedHeap {
  uint32_t memory_type_bits = 0;
  uint64_t size = 0;
  uint64_t alignment = 1;  // largest alignment of a resident
  std::vector<uint32_t> resources;
};

struct PlanStats {
  uint64_t transient_bytes_aliased = 0;    // sum of heap sizes
  uint64_t transient_bytes_unaliased = 0;  // sum of transient sizes
  uint32_t barrier_count = 0;              // resource + global barriers, final ones included
};

struct CompiledPlan {
  std::vector<PlannedPass> passes;  // execution order
  std::vector<Barrier> final_barriers;  // after the last pass: imports to their final state
  std::vector<PlannedResource> resources;  // same indices as Graph::resources()
  std::vector<PlannedHeap> heaps;
  std::vector<PlannedPass> culled_passes;  // declaration order, no barriers
  PlanStats stats;
  CompileOptions options;
  uint64_t shape_hash = 0;  // Graph::shape_hash(options) of the compiled graph

  // Deterministic text used by the golden tests; flags and layouts printed by name.
  std::string to_text() const;
  std::string to_json() const;
  // Graphviz: passes are boxes (culled ones grey), resources ellipses labelled with
  // their placement, edges for reads (resource -> pass) and writes (pass -> resource).
  std::string to_dot() const;
};

}  // namespace rg
