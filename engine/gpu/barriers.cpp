#include "gpu/barriers.h"

namespace avsm::gpu {

VkBufferMemoryBarrier2 make_buffer_barrier(VkBuffer buffer, Access src, Access dst) {
  VkBufferMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_BUFFER_MEMORY_BARRIER_2};
  barrier.srcStageMask = src.stage;
  barrier.srcAccessMask = src.access;
  barrier.dstStageMask = dst.stage;
  barrier.dstAccessMask = dst.access;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.buffer = buffer;
  barrier.size = VK_WHOLE_SIZE;
  return barrier;
}

VkImageMemoryBarrier2 make_image_barrier(VkImage image, VkImageSubresourceRange range, VkImageLayout old_layout,
                                         VkImageLayout new_layout, Access src, Access dst) {
  VkImageMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_IMAGE_MEMORY_BARRIER_2};
  barrier.srcStageMask = src.stage;
  barrier.srcAccessMask = src.access;
  barrier.dstStageMask = dst.stage;
  barrier.dstAccessMask = dst.access;
  barrier.oldLayout = old_layout;
  barrier.newLayout = new_layout;
  barrier.srcQueueFamilyIndex = barrier.dstQueueFamilyIndex = VK_QUEUE_FAMILY_IGNORED;
  barrier.image = image;
  barrier.subresourceRange = range;
  return barrier;
}

VkMemoryBarrier2 make_memory_barrier(Access src, Access dst) {
  VkMemoryBarrier2 barrier{VK_STRUCTURE_TYPE_MEMORY_BARRIER_2};
  barrier.srcStageMask = src.stage;
  barrier.srcAccessMask = src.access;
  barrier.dstStageMask = dst.stage;
  barrier.dstAccessMask = dst.access;
  return barrier;
}

void buffer_barrier(VkCommandBuffer cmd, VkBuffer buffer, Access src, Access dst) {
  VkBufferMemoryBarrier2 barrier = make_buffer_barrier(buffer, src, dst);
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.bufferMemoryBarrierCount = 1;
  dep.pBufferMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void image_barrier(VkCommandBuffer cmd, VkImage image, VkImageSubresourceRange range, VkImageLayout old_layout,
                   VkImageLayout new_layout, Access src, Access dst) {
  VkImageMemoryBarrier2 barrier = make_image_barrier(image, range, old_layout, new_layout, src, dst);
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.imageMemoryBarrierCount = 1;
  dep.pImageMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dep);
}

void memory_barrier(VkCommandBuffer cmd, Access src, Access dst) {
  VkMemoryBarrier2 barrier = make_memory_barrier(src, dst);
  VkDependencyInfo dep{VK_STRUCTURE_TYPE_DEPENDENCY_INFO};
  dep.memoryBarrierCount = 1;
  dep.pMemoryBarriers = &barrier;
  vkCmdPipelineBarrier2(cmd, &dep);
}

}  // namespace avsm::gpu
