#pragma once
// Small sync2 barrier helpers for work outside the frame graph (uploads,
// readbacks, tests). Inside a frame, the graph plans every barrier.
#include <vulkan/vulkan.h>

namespace avsm::gpu {

struct Access {
  VkPipelineStageFlags2 stage = VK_PIPELINE_STAGE_2_NONE;
  VkAccessFlags2 access = VK_ACCESS_2_NONE;
};

// The sync2 structs, for callers that batch several barriers in one call.
VkBufferMemoryBarrier2 make_buffer_barrier(VkBuffer buffer, Access src, Access dst);
VkImageMemoryBarrier2 make_image_barrier(VkImage image, VkImageSubresourceRange range, VkImageLayout old_layout,
                                         VkImageLayout new_layout, Access src, Access dst);
VkMemoryBarrier2 make_memory_barrier(Access src, Access dst);

// One barrier, recorded at once.
void buffer_barrier(VkCommandBuffer cmd, VkBuffer buffer, Access src, Access dst);
void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range, VkImageLayout old_layout,
                   VkImageLayout new_layout, Access src, Access dst);
void memory_barrier(VkCommandBuffer cmd, Access src, Access dst);

// Common access points.
inline constexpr Access kComputeWrite{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT};
inline constexpr Access kComputeRead{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT, VK_ACCESS_2_SHADER_STORAGE_READ_BIT};
inline constexpr Access kTransferWrite{VK_PIPELINE_STAGE_2_COPY_BIT | VK_PIPELINE_STAGE_2_CLEAR_BIT,
                                       VK_ACCESS_2_TRANSFER_WRITE_BIT};
inline constexpr Access kTransferRead{VK_PIPELINE_STAGE_2_COPY_BIT, VK_ACCESS_2_TRANSFER_READ_BIT};
inline constexpr Access kHostRead{VK_PIPELINE_STAGE_2_HOST_BIT, VK_ACCESS_2_HOST_READ_BIT};
inline constexpr Access kColorWrite{VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT,
                                    VK_ACCESS_2_COLOR_ATTACHMENT_WRITE_BIT};
inline constexpr Access kAllShaderRead{VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_ACCESS_2_SHADER_READ_BIT};

}  // namespace avsm::gpu
