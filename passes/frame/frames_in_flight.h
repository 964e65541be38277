#pragma once
// Frames in flight: the CPU records frame N+1 while the GPU still runs frame N (up to
// kMaxFramesInFlight frames; renderer/frame_slots.h holds each frame's command buffer,
// fence and executor). Every frame records into a slot, and a slot is recorded again
// only after its previous frame's fence signalled. So:
//   - what a frame's passes write for the CPU (readbacks, counters) and what the CPU
//     writes for a frame has one copy per slot (FrameBuffers): no frame touches memory
//     that an earlier frame still in flight uses, and a frame's results stay readable
//     until its slot is recorded again;
//   - what the GPU keeps from frame to frame (the shadow maps, the output images) has
//     one copy, ordered by the one queue: each frame imports it in the state the frame
//     before left it in (rewritten_after), so its first access waits for that frame's.
#include <rendergraph/usage.h>

#include <cstdint>
#include <vector>

#include "gpu/resources.h"

namespace avsm::passes {

constexpr uint32_t kMaxFramesInFlight = 3;

// Throws std::invalid_argument unless 1 <= count <= kMaxFramesInFlight.
void check_frames_in_flight(uint32_t count);

// The import state of a resource every frame rewrites whole, which the frame before
// (perhaps still running) left in `final_state`: the first access waits for that
// frame's accesses (its final barrier made its writes visible in that scope), and the
// contents are discarded (layout UNDEFINED, as no earlier frame's image is read).
inline rg::ImportState rewritten_after(rg::ImportState final_state) {
  final_state.layout = VK_IMAGE_LAYOUT_UNDEFINED;
  return final_state;
}

// One buffer per frame slot, each as created (named "<name> (frame i)" when there are
// several). Knows its number of frames in flight before it has buffers.
class FrameBuffers {
 public:
  // Makes the buffers, one per frame in flight, as `desc` says.
  void create(const gpu::Context& ctx, gpu::BufferDesc desc);
  // Another number of frames in flight (throws std::invalid_argument outside
  // 1..kMaxFramesInFlight): buffers already created are made again (contents lost).
  void set_frames(const gpu::Context& ctx, uint32_t frames);

  const gpu::Buffer& operator[](uint32_t slot) const { return buffers_.at(slot); }
  uint32_t frames() const { return frames_; }
  explicit operator bool() const { return !buffers_.empty(); }

 private:
  uint32_t frames_ = 1;
  gpu::BufferDesc desc_;
  std::vector<gpu::Buffer> buffers_;
};

// Buffers replaced while frames in flight may still use them (a capture that grew):
// each is kept until every frame that was in flight when it was replaced has finished,
// instead of waiting for the device to idle. A frame is in flight from its declaration
// into a slot to its finish; declaring into the slot again also means it finished.
class RetiredBuffers {
 public:
  // A frame is declared into `slot` (the frame it held before has completed).
  void declared(uint32_t slot);
  // The frame in `slot` has completed.
  void finished(uint32_t slot);
  // Keeps `buffer` (if any) until the frames in flight now have finished.
  void retire(gpu::Buffer buffer);

 private:
  void release(uint32_t slot);
  struct Kept {
    uint32_t waiting_slots;  // bit s: the frame in slot s still uses it
    gpu::Buffer buffer;
  };
  uint32_t in_flight_ = 0;  // bit s: slot s holds a frame in flight
  std::vector<Kept> kept_;
};

}  // namespace avsm::passes
