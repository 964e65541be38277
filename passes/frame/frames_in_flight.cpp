#include "passes/frame/frames_in_flight.h"

#include <stdexcept>
#include <string>

namespace avsm::passes {

void check_frames_in_flight(uint32_t count) {
  if (count < 1 || count > kMaxFramesInFlight)
    throw std::invalid_argument(std::to_string(count) + " frames in flight; use 1 to " +
                                std::to_string(kMaxFramesInFlight) + " (--frames-in-flight)");
}

void FrameBuffers::create(const gpu::Context& ctx, gpu::BufferDesc desc) {
  desc_ = std::move(desc);
  buffers_.clear();
  for (uint32_t slot = 0; slot < frames_; ++slot) {
    gpu::BufferDesc one = desc_;
    if (frames_ > 1) one.name += " (frame " + std::to_string(slot) + ")";
    buffers_.push_back(gpu::Buffer::create(ctx, one));
  }
}

void FrameBuffers::set_frames(const gpu::Context& ctx, uint32_t frames) {
  check_frames_in_flight(frames);
  if (frames == frames_) return;
  frames_ = frames;
  if (!buffers_.empty()) create(ctx, desc_);
}

void RetiredBuffers::declared(uint32_t slot) {
  release(slot);
  in_flight_ |= 1u << slot;
}

void RetiredBuffers::finished(uint32_t slot) {
  release(slot);
  in_flight_ &= ~(1u << slot);
}

void RetiredBuffers::retire(gpu::Buffer buffer) {
  if (buffer && in_flight_ != 0) kept_.push_back({in_flight_, std::move(buffer)});
}

void RetiredBuffers::release(uint32_t slot) {
  for (Kept& kept : kept_) kept.waiting_slots &= ~(1u << slot);
  std::erase_if(kept_, [](const Kept& kept) { return kept.waiting_slots == 0; });
}

}  // namespace avsm::passes
