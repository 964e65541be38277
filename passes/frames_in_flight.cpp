#include "passes/frames_in_flight.h"

#include <stdexcept>
#include <string>

namespace avsm::passes {

void check_frames_in_flight(uint32_t count) {
  if (count < 1 || count > kMaxFramesInFlight)
    throw std::invalid_argument(std::to_string(count) + " frames in flight; use 1 to " +
                                std::to_string(kMaxFramesInFlight) + " (--frames-in-flight)");
}

FrameBuffers::FrameBuffers(const gpu::Context& ctx, gpu::BufferDesc desc, uint32_t frames) : desc_(std::move(desc)) {
  check_frames_in_flight(frames);
  for (uint32_t slot = 0; slot < frames; ++slot) {
    gpu::BufferDesc one = desc_;
    if (frames > 1) one.name += " (frame " + std::to_string(slot) + ")";
    buffers_.push_back(gpu::Buffer::create(ctx, one));
  }
}

}  // namespace avsm::passes
