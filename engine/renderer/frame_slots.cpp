#include "renderer/frame_slots.h"

#include <string>

#include "gpu/context.h"
#include "gpu/vk_check.h"
#include "passes/frame/frames_in_flight.h"

namespace avsm::renderer {

FrameSlots::FrameSlots(gpu::Context& ctx, gpu::TimestampMode timestamps, uint32_t count) : ctx_(ctx) {
  passes::check_frames_in_flight(count);
  slots_.resize(count);
  for (uint32_t i = 0; i < count; ++i) {
    Slot& slot = slots_[i];
    slot.index = i;
    slot.cmd = ctx.allocate_command_buffer("frame slot " + std::to_string(i));
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    VK_CHECK(vkCreateFence(ctx.device(), &fence_info, nullptr, &slot.fence));
    slot.executor = std::make_unique<rg::vulkan::Executor>(ctx, timestamps);
  }
}

FrameSlots::~FrameSlots() {
  for (Slot& slot : slots_) {
    if (slot.in_flight) vkWaitForFences(ctx_.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX);
    vkDestroyFence(ctx_.device(), slot.fence, nullptr);
    vkFreeCommandBuffers(ctx_.device(), ctx_.command_pool(), 1, &slot.cmd);
  }
}

void FrameSlots::finish(Slot& slot, const Finished& finished) {
  VK_CHECK(vkWaitForFences(ctx_.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX));
  VK_CHECK(vkResetFences(ctx_.device(), 1, &slot.fence));
  slot.in_flight = false;
  last_finished_ = slot.index;
  if (finished) finished(slot);
}

FrameSlots::Slot& FrameSlots::acquire(const Finished& finished) {
  Slot& slot = slots_[next_];
  next_ = (next_ + 1) % count();
  if (slot.in_flight) finish(slot, finished);
  return slot;
}

void FrameSlots::submit(Slot& slot, VkSemaphore wait, VkPipelineStageFlags2 wait_stages, VkSemaphore signal,
                        uint64_t wait_value) {
  VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
  cmd_info.commandBuffer = slot.cmd;
  VkSemaphoreSubmitInfo wait_info{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  wait_info.semaphore = wait;
  wait_info.stageMask = wait_stages;
  wait_info.value = wait_value;
  VkSemaphoreSubmitInfo signal_info{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
  signal_info.semaphore = signal;
  signal_info.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
  VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
  submit.commandBufferInfoCount = 1;
  submit.pCommandBufferInfos = &cmd_info;
  submit.waitSemaphoreInfoCount = wait ? 1 : 0;
  submit.pWaitSemaphoreInfos = &wait_info;
  submit.signalSemaphoreInfoCount = signal ? 1 : 0;
  submit.pSignalSemaphoreInfos = &signal_info;
  VK_CHECK(vkQueueSubmit2(ctx_.graphics_queue().handle, 1, &submit, slot.fence));
  slot.in_flight = true;
}

void FrameSlots::finish_completed(const Finished& finished) {
  for (uint32_t i = 0; i < count(); ++i) {
    Slot& slot = slots_[(next_ + i) % count()];
    if (!slot.in_flight) continue;
    if (vkGetFenceStatus(ctx_.device(), slot.fence) != VK_SUCCESS) return;  // later frames finish after it
    finish(slot, finished);
  }
}

void FrameSlots::finish_all(const Finished& finished) {
  // Oldest first: the slots from next_ on, in turn.
  for (uint32_t i = 0; i < count(); ++i) {
    Slot& slot = slots_[(next_ + i) % count()];
    if (slot.in_flight) finish(slot, finished);
  }
}

}  // namespace avsm::renderer
