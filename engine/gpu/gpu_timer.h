#pragma once
// Per-pass GPU timing with timestamp queries.
//
// Two ways to turn timestamps into pass durations:
//  - Exact: a timestamp before and after each scope (real GPUs).
//  - EndToEnd: one timestamp at the frame start and one after each scope; a
//    scope's duration is its end minus the previous scope's end, and each
//    kept timestamp is followed by an empty barrier that makes the driver
//    resolve it at once.
//
// Why EndToEnd exists (measured on lavapipe, Mesa 22.3): once anything has been
// rendered, a timestamp is not resolved when it is written but when the driver
// next flushes its rasterizer, asynchronously. Compute dispatches do not flush,
// so a timestamp written before a dispatch reads roughly the time that dispatch
// ends, and a compute pass between two timestamps measures ~0 ms. A pipeline
// barrier makes lavapipe flush and wait, which resolves the timestamp before
// anything else runs. The barrier has dstStageMask NONE: it orders nothing after
// it, so it cannot hide a missing barrier from synchronization validation.
// Only ends are kept: consecutive ends are right when passes run one after
// another, which is how lavapipe runs them, and they add up to the frame time.
// calibrate_timestamps() measures which mode a device needs.
#include <vulkan/vulkan.h>

#include <cstdint>
#include <string>
#include <vector>

namespace avsm::gpu {

class Context;
class ShaderLibrary;

enum class TimestampMode { Exact, EndToEnd };
const char* to_string(TimestampMode mode);

struct TimestampCalibration {
  TimestampMode mode = TimestampMode::Exact;
  double dispatch_ms_timestamps = 0;  // what begin/end timestamps said
  double dispatch_ms_host = 0;        // what the host clock said around the submission
};

// Runs a known compute workload between two timestamps and compares with the
// host clock. AVSM_TIMESTAMP_MODE=exact|end-to-end overrides the measurement.
TimestampCalibration calibrate_timestamps(const Context& ctx, const ShaderLibrary& shaders);

struct ScopeTiming {
  std::string name;
  double gpu_ms = 0;
};

// Times up to a frame's number of scopes, which begin_frame() is told: the query pool
// grows with the frame graph (a scene of many lights has many passes), so no scene
// meets a fixed limit.
class GpuTimer {
 public:
  // `scopes`: the query pool's first size (it grows as frames need).
  GpuTimer(const Context& ctx, uint32_t scopes, TimestampMode mode);
  ~GpuTimer();
  GpuTimer(const GpuTimer&) = delete;
  GpuTimer& operator=(const GpuTimer&) = delete;

  // Starts a frame of at most `scopes` scopes, growing the query pool to fit; the frame
  // this timer recorded before must have completed (as for every resource it reuses).
  // Scopes must not nest, and must be recorded in submission order.
  void begin_frame(VkCommandBuffer cmd, uint32_t scopes);
  uint32_t begin_scope(VkCommandBuffer cmd, const std::string& name);
  void end_scope(VkCommandBuffer cmd, uint32_t scope);

  // After the frame's command buffer has completed.
  std::vector<ScopeTiming> read_scopes() const;
  TimestampMode mode() const { return mode_; }

 private:
  void write_timestamp(VkCommandBuffer cmd, uint32_t query);
  void create_pool(uint32_t scopes);
  const Context& ctx_;
  VkQueryPool pool_ = VK_NULL_HANDLE;
  uint32_t max_scopes_;
  TimestampMode mode_;
  std::vector<std::string> names_;
};

}  // namespace avsm::gpu
