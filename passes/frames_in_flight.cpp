#include "passes/frames_in_flight.h"

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

}  // namespace avsm::passes
