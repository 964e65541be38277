#pragma once
// Figures per camera pixel and light that the CPU reads after a frame (shadow quality,
// shadow resolution): one host-readable buffer per frame in flight, laid out
// [light * width * height + y * width + x], row 0 at the top.
#include <algorithm>
#include <cstdint>
#include <cstring>
#include <stdexcept>
#include <string>
#include <vector>

#include "gpu/context.h"
#include "passes/frame/frames_in_flight.h"

namespace avsm::passes {

template <class T>
class PerPixelResults {
 public:
  // Sizes the buffers for `lights` lights on a width x height image. Throws
  // std::invalid_argument, naming `what`, when they would pass the device's storage
  // buffer range.
  void set_size(const gpu::Context& ctx, uint32_t width, uint32_t height, uint32_t lights, const std::string& what) {
    const uint64_t bytes = uint64_t(width) * height * std::max(lights, 1u) * sizeof(T);
    const uint64_t range = ctx.info().max_storage_buffer_range;
    if (bytes > range)
      throw std::invalid_argument(what + ": " + std::to_string(width) + "x" + std::to_string(height) + " pixels for " +
                                  std::to_string(lights) + " lights need " + std::to_string(bytes >> 20) +
                                  " MiB, more than the device's " + std::to_string(range >> 20) +
                                  " MiB storage buffer range; capture smaller images (--width/--height) or fewer lights");
    width_ = width;
    height_ = height;
    lights_ = lights;
    buffers_.create(ctx, {std::max<uint64_t>(uint64_t(width) * height * lights, 1) * sizeof(T),
                          VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryLocation::HostReadback, what});
  }
  void set_frames(const gpu::Context& ctx, uint32_t count) { buffers_.set_frames(ctx, count); }

  const gpu::Buffer& operator[](uint32_t slot) const { return buffers_[slot]; }
  // After the frame recorded into `slot` completed.
  std::vector<T> read(uint32_t slot) const {
    std::vector<T> out(size_t(width_) * height_ * lights_);
    if (!out.empty()) std::memcpy(out.data(), buffers_[slot].mapped(), out.size() * sizeof(T));
    return out;
  }
  uint32_t width() const { return width_; }
  uint32_t height() const { return height_; }
  uint32_t light_count() const { return lights_; }

 private:
  FrameBuffers buffers_;
  uint32_t width_ = 0, height_ = 0, lights_ = 0;
};

}  // namespace avsm::passes
