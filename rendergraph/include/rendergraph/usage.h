#pragma once
// How a pass uses a resource, and the single table that turns a usage into Vulkan
// synchronisation terms. The barrier planner and the Vulkan executor both read this
// table (the executor to derive VkImageUsageFlags / VkBufferUsageFlags), so a usage
// means the same thing everywhere.
#include <rendergraph/types.h>

#include <initializer_list>

namespace rg {

enum class Usage : uint8_t {
  Sampled,               // texture: sampled image; buffer: uniform texel buffer
  StorageRead,           // storage image / storage buffer, read only
  StorageWrite,          // storage image / storage buffer, write only
  StorageReadWrite,      // storage image / storage buffer, read and write (atomics, in-place)
  UniformRead,           // uniform buffer (buffers only)
  ColorAttachment,       // colour attachment (textures only, graphics passes)
  DepthAttachmentWrite,  // depth test + write (textures only, graphics passes)
  DepthAttachmentRead,   // read-only depth test (textures only, graphics passes)
  TransferSrc,           // copy/blit source
  TransferDst,           // copy/blit/clear destination
  IndirectRead,          // indirect draw/dispatch arguments (buffers only)
  VertexRead,            // vertex buffer (buffers only, graphics passes)
  IndexRead,             // index buffer (buffers only, graphics passes)
  HostRead,              // read by the CPU after the graph: an ImportState, not a pass usage
  Present,               // handed to the presentation engine: an ImportState, not a pass usage
};
inline constexpr uint32_t kUsageCount = 15;

const char* to_string(Usage usage);

// A small set of usages (one bit per Usage).
class UsageSet {
 public:
  constexpr UsageSet() = default;
  constexpr UsageSet(std::initializer_list<Usage> usages) {
    for (Usage usage : usages) insert(usage);
  }

  constexpr void insert(Usage usage) { bits_ |= bit(usage); }
  constexpr void insert(UsageSet other) { bits_ |= other.bits_; }
  constexpr bool contains(Usage usage) const { return (bits_ & bit(usage)) != 0; }
  constexpr bool empty() const { return bits_ == 0; }
  constexpr uint32_t bits() const { return bits_; }

  template <class Fn>
  void for_each(Fn&& fn) const {
    for (uint32_t i = 0; i < kUsageCount; ++i)
      if (bits_ & (1u << i)) fn(static_cast<Usage>(i));
  }

  bool operator==(const UsageSet&) const = default;

 private:
  static constexpr uint32_t bit(Usage usage) { return 1u << static_cast<uint32_t>(usage); }
  uint32_t bits_ = 0;
};

// One row of the usage table, resolved for the queue type of the pass.
struct UsageInfo {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;  // what a texture must be in; unused for buffers
  bool is_write = false;                             // the usage modifies the resource
  VkImageUsageFlags image_usage = 0;                 // what a VkImage needs to allow this usage
  VkBufferUsageFlags buffer_usage = 0;               // what a VkBuffer needs to allow this usage
};

// Shader usages resolve to PRE_RASTERIZATION_SHADERS|FRAGMENT_SHADER in graphics passes
// and COMPUTE_SHADER in compute passes; fixed-function usages ignore the queue type.
UsageInfo usage_info(Usage usage, QueueType queue);

// Why `usage` is not allowed for a pass on `queue` touching a resource of `kind`, or
// nullptr when it is. E.g. ColorAttachment in a compute pass, UniformRead on a texture.
const char* usage_problem(Usage usage, QueueType queue, ResourceKind kind);

// Creation flags a resource needs for every usage it sees in the plan. The Vulkan
// executor creates images/buffers with exactly these, and its MemoryModel should query
// memory requirements with the same flags.
VkImageUsageFlags image_usage_flags(UsageSet usages);
VkBufferUsageFlags buffer_usage_flags(UsageSet usages);

// Aspect of a whole-image barrier for `format` (depth and/or stencil, else colour).
VkImageAspectFlags aspect_flags(VkFormat format);

// The write bits of an access mask (SHADER_STORAGE_WRITE, COLOR_ATTACHMENT_WRITE, ...).
VkAccessFlags2 write_access_bits(VkAccessFlags2 access);

// The state an imported resource is in before the graph runs, or must be left in after
// it: the stages/accesses that last touched it (or will touch it next) and the layout
// (textures). Build one from a usage, or spell it out for e.g. a swapchain image whose
// acquire semaphore is waited at COLOR_ATTACHMENT_OUTPUT.
struct ImportState {
  VkPipelineStageFlags2 stages = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
  VkImageLayout layout = VK_IMAGE_LAYOUT_UNDEFINED;

  // Nothing pending and no contents worth keeping (layout UNDEFINED). As a final state:
  // "leave it however the last pass left it".
  static ImportState none() { return {}; }
  static ImportState of(Usage usage, QueueType queue = QueueType::Graphics);

  bool operator==(const ImportState&) const = default;
};

}  // namespace rg
