// The usage table: (Usage, queue type) -> stages, accesses, layout, write, creation flags.
// Everything else in the graph derives its Vulkan terms from here.
#include <rendergraph/usage.h>

#include <array>

namespace rg {
namespace {

// Marks a usage whose stages are the shader stages of the pass's queue.
constexpr VkPipelineStageFlags2 kShaderStages = ~VkPipelineStageFlags2{0};

constexpr uint8_t kGraphics = 1u << static_cast<int>(QueueType::Graphics);
constexpr uint8_t kCompute = 1u << static_cast<int>(QueueType::Compute);
constexpr uint8_t kTransfer = 1u << static_cast<int>(QueueType::Transfer);
constexpr uint8_t kAnyQueue = kGraphics | kCompute | kTransfer;
constexpr uint8_t kNoQueue = 0;  // only meaningful as an ImportState (host, presentation)

struct Row {
  Usage usage;
  VkPipelineStageFlags2 stages;
  VkAccessFlags2 access;
  VkImageLayout layout;  // UNDEFINED: not usable on textures
  bool is_write;
  uint8_t queues;     // queue types whose passes may use it
  bool for_buffers;   // usable on buffers
  VkImageUsageFlags image_usage;
  VkBufferUsageFlags buffer_usage;
};

// clang-format off
constexpr std::array<Row, kUsageCount> kTable = {{
  {Usage::Sampled, kShaderStages, VK_ACCESS_2_SHADER_SAMPLED_READ_BIT,
   VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL, false, kGraphics | kCompute, true,
   VK_IMAGE_USAGE_SAMPLED_BIT, VK_BUFFER_USAGE_UNIFORM_TEXEL_BUFFER_BIT},
  {Usage::StorageRead, kShaderStages, VK_ACCESS_2_SHADER_STORAGE_READ_BIT,
   VK_IMAGE_LAYOUT_GENERAL, false, kGraphics | kCompute, true,
   VK_IMAGE_USAGE_STORAGE_BIT, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT},
  {Usage::StorageWrite, kShaderStages, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
   VK_IMAGE_LAYOUT_GENERAL, true, kGraphics | kCompute, true,
   VK_IMAGE_USAGE_STORAGE_BIT, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT},
  {Usage::StorageReadWrite, kShaderStages,
   VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT,
   VK_IMAGE_LAYOUT_GENERAL, true, kGraphics | kCompute, true,
   VK_IMAGE_USAGE_STORAGE_BIT, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT},
  {Usage::UniformRead, kShaderStages, VK_ACCESS_2_UNIFORM_READ_BIT,
   VK_IMAGE_LAYOUT_UNDEFINED, false, kGraphics | kCompute, true,
   0, VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT},
  {Usage::ColorAttachment, VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
   VK_ACCESS_2_COLOR_ATTACHMENT_READ_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT,
   VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, true, kGraphics, false,
   VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT, 0},
  {Usage::DepthAttachmentWrite,
   VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
   VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT | VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT,
   VK_IMAGE_LAYOUT_DEPTH_STENCIL_ATTACHMENT_OPTIMAL, true, kGraphics, false,
   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, 0},
  {Usage::DepthAttachmentRead,
   VK_PIPELINE_STAGE_2_EARLY_FRAGMENT_TESTS_BIT | VK_PIPELINE_STAGE_2_LATE_FRAGMENT_TESTS_BIT,
   VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_READ_BIT,
   VK_IMAGE_LAYOUT_DEPTH_STENCIL_READ_ONLY_OPTIMAL, false, kGraphics, false,
   VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT, 0},
  {Usage::TransferSrc, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_READ_BIT,
   VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL, false, kAnyQueue, true,
   VK_IMAGE_USAGE_TRANSFER_SRC_BIT, VK_BUFFER_USAGE_TRANSFER_SRC_BIT},
  {Usage::TransferDst, VK_PIPELINE_STAGE_2_TRANSFER_BIT, VK_ACCESS_2_TRANSFER_WRITE_BIT,
   VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL, true, kAnyQueue, true,
   VK_IMAGE_USAGE_TRANSFER_DST_BIT, VK_BUFFER_USAGE_TRANSFER_DST_BIT},
  {Usage::IndirectRead, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT,
   VK_IMAGE_LAYOUT_UNDEFINED, false, kGraphics | kCompute, true,
   0, VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT},
  {Usage::VertexRead, VK_PIPELINE_STAGE_2_VERTEX_ATTRIBUTE_INPUT_BIT, VK_ACCESS_2_VERTEX_ATTRIBUTE_READ_BIT,
   VK_IMAGE_LAYOUT_UNDEFINED, false, kGraphics, true,
   0, VK_BUFFER_USAGE_VERTEX_BUFFER_BIT},
  {Usage::IndexRead, VK_PIPELINE_STAGE_2_INDEX_INPUT_BIT, VK_ACCESS_2_INDEX_READ_BIT,
   VK_IMAGE_LAYOUT_UNDEFINED, false, kGraphics, true,
   0, VK_BUFFER_USAGE_INDEX_BUFFER_BIT},
  {Usage::HostRead, VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT,
   VK_IMAGE_LAYOUT_GENERAL, false, kNoQueue, true,
   0, 0},
  // Presentation waits on a semaphore, not on a pipeline stage: dst stage NONE is the
  // sync2 idiom for the transition to PRESENT_SRC.
  {Usage::Present, VK_PIPELINE_STAGE_2_NONE, VK_ACCESS_2_NONE,
   VK_IMAGE_LAYOUT_PRESENT_SRC_KHR, false, kNoQueue, false,
   0, 0},
}};
// clang-format on

const Row& row(Usage usage) { return kTable[static_cast<size_t>(usage)]; }

VkPipelineStageFlags2 shader_stages(QueueType queue) {
  switch (queue) {
    case QueueType::Graphics:
      return VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT;
    case QueueType::Compute:
      return VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT;
    case QueueType::Transfer:
      return VK_PIPELINE_STAGE_2_NONE;  // rejected by usage_problem()
  }
  return VK_PIPELINE_STAGE_2_NONE;
}

// The table must list the usages in enum order: row(usage) indexes it directly.
constexpr bool table_in_enum_order() {
  for (size_t i = 0; i < kTable.size(); ++i)
    if (static_cast<size_t>(kTable[i].usage) != i) return false;
  return true;
}
static_assert(table_in_enum_order());

}  // namespace

const char* to_string(Usage usage) {
  switch (usage) {
    case Usage::Sampled: return "Sampled";
    case Usage::StorageRead: return "StorageRead";
    case Usage::StorageWrite: return "StorageWrite";
    case Usage::StorageReadWrite: return "StorageReadWrite";
    case Usage::UniformRead: return "UniformRead";
    case Usage::ColorAttachment: return "ColorAttachment";
    case Usage::DepthAttachmentWrite: return "DepthAttachmentWrite";
    case Usage::DepthAttachmentRead: return "DepthAttachmentRead";
    case Usage::TransferSrc: return "TransferSrc";
    case Usage::TransferDst: return "TransferDst";
    case Usage::IndirectRead: return "IndirectRead";
    case Usage::VertexRead: return "VertexRead";
    case Usage::IndexRead: return "IndexRead";
    case Usage::HostRead: return "HostRead";
    case Usage::Present: return "Present";
  }
  return "?";
}

UsageInfo usage_info(Usage usage, QueueType queue) {
  const Row& r = row(usage);
  UsageInfo info;
  info.stages = r.stages == kShaderStages ? shader_stages(queue) : r.stages;
  info.access = r.access;
  info.layout = r.layout;
  info.is_write = r.is_write;
  info.image_usage = r.image_usage;
  info.buffer_usage = r.buffer_usage;
  return info;
}

const char* usage_problem(Usage usage, QueueType queue, ResourceKind kind) {
  const Row& r = row(usage);
  if (r.queues == kNoQueue) return "is only valid as an import state, not in a pass";
  if (kind == ResourceKind::Texture && r.layout == VK_IMAGE_LAYOUT_UNDEFINED) return "is for buffers only";
  if (kind == ResourceKind::Buffer && !r.for_buffers) return "is for textures only";
  if ((r.queues & (1u << static_cast<int>(queue))) == 0) {
    switch (queue) {
      case QueueType::Graphics: return "is not available in a graphics pass";
      case QueueType::Compute: return "is not available in a compute pass";
      case QueueType::Transfer: return "is not available in a transfer pass";
    }
  }
  return nullptr;
}

VkImageUsageFlags image_usage_flags(UsageSet usages) {
  VkImageUsageFlags flags = 0;
  usages.for_each([&](Usage usage) { flags |= row(usage).image_usage; });
  return flags;
}

VkBufferUsageFlags buffer_usage_flags(UsageSet usages) {
  VkBufferUsageFlags flags = 0;
  usages.for_each([&](Usage usage) { flags |= row(usage).buffer_usage; });
  return flags;
}

VkImageAspectFlags aspect_flags(VkFormat format) {
  switch (format) {
    case VK_FORMAT_D16_UNORM:
    case VK_FORMAT_X8_D24_UNORM_PACK32:
    case VK_FORMAT_D32_SFLOAT:
      return VK_IMAGE_ASPECT_DEPTH_BIT;
    case VK_FORMAT_S8_UINT:
      return VK_IMAGE_ASPECT_STENCIL_BIT;
    case VK_FORMAT_D16_UNORM_S8_UINT:
    case VK_FORMAT_D24_UNORM_S8_UINT:
    case VK_FORMAT_D32_SFLOAT_S8_UINT:
      return VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT;
    default:
      return VK_IMAGE_ASPECT_COLOR_BIT;
  }
}

VkAccessFlags2 write_access_bits(VkAccessFlags2 access) {
  constexpr VkAccessFlags2 kWrites =
      VK_ACCESS_2_SHADER_WRITE_BIT | VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT |
      VK_ACCESS_2_DEPTH_STENCIL_ATTACHMENT_WRITE_BIT | VK_ACCESS_2_TRANSFER_WRITE_BIT |
      VK_ACCESS_2_HOST_WRITE_BIT | VK_ACCESS_2_MEMORY_WRITE_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT |
      VK_ACCESS_2_ACCELERATION_STRUCTURE_WRITE_BIT_KHR | VK_ACCESS_2_TRANSFORM_FEEDBACK_WRITE_BIT_EXT |
      VK_ACCESS_2_TRANSFORM_FEEDBACK_COUNTER_WRITE_BIT_EXT | VK_ACCESS_2_COMMAND_PREPROCESS_WRITE_BIT_NV;
  return access & kWrites;
}

ImportState ImportState::of(Usage usage, QueueType queue) {
  UsageInfo info = usage_info(usage, queue);
  return ImportState{info.stages, info.access, info.layout};
}

}  // namespace rg
