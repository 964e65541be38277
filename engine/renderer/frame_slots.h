#pragma once
// Frames in flight (passes/frame/frames_in_flight.h): one slot per frame the CPU may record
// ahead of the GPU, each with its command buffer, fence and frame-graph executor (whose
// transient heaps and timestamp queries serve the frame that last used the slot, so
// they are never replaced while the GPU uses them). Slots are used in turn and their
// frames submitted to the one queue in order, so frames complete in that order; a
// frame's results are read when its fence signals, as its slot is needed again or at
// the end (finish_all), never by idling the device.
#include <rendergraph/vulkan/executor.h>

#include <functional>
#include <memory>
#include <vector>

#include "gpu/gpu_timer.h"

namespace avsm::gpu {
class Context;
}

namespace avsm::renderer {

class FrameSlots {
 public:
  struct Slot {
    uint32_t index = 0;
    VkCommandBuffer cmd = VK_NULL_HANDLE;
    VkFence fence = VK_NULL_HANDLE;
    std::unique_ptr<rg::vulkan::Executor> executor;
    bool in_flight = false;  // submitted and not finished yet
  };
  using Finished = std::function<void(Slot&)>;

  // Throws std::invalid_argument for a count outside 1..passes::kMaxFramesInFlight.
  FrameSlots(gpu::Context& ctx, gpu::TimestampMode timestamps, uint32_t count);
  ~FrameSlots();  // waits for the frames in flight
  FrameSlots(const FrameSlots&) = delete;
  FrameSlots& operator=(const FrameSlots&) = delete;

  uint32_t count() const { return uint32_t(slots_.size()); }
  // The slot for the next frame, its command buffer ready to begin. When it still
  // holds a frame in flight (the oldest), waits for that frame's fence and hands the
  // slot to `finished` first.
  Slot& acquire(const Finished& finished);
  // Submits the slot's recorded command buffer; its fence signals when it completes.
  // A window frame waits for its acquired image (`wait` at `wait_stages`) and signals
  // `signal` for the present. A timeline semaphore `wait` is waited for to `wait_value`.
  void submit(Slot& slot, VkSemaphore wait = VK_NULL_HANDLE, VkPipelineStageFlags2 wait_stages = 0,
              VkSemaphore signal = VK_NULL_HANDLE, uint64_t wait_value = 0);
  // Hands the frames in flight that have completed to `finished`, oldest first, without waiting.
  void finish_completed(const Finished& finished);
  // Waits for every frame in flight, oldest first, handing each to `finished`.
  void finish_all(const Finished& finished);
  // The executor of the last frame finished (its plan and timestamp mode).
  const rg::vulkan::Executor& last_finished_executor() const { return *slots_[last_finished_].executor; }

 private:
  void finish(Slot& slot, const Finished& finished);

  gpu::Context& ctx_;
  std::vector<Slot> slots_;
  uint32_t next_ = 0;           // the slot acquire() hands out next: the oldest
  uint32_t last_finished_ = 0;
};

}  // namespace avsm::renderer
