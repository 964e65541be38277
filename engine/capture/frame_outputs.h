#pragma once
// What one captured frame leaves on disk, written the same way by avsm-capture
// and by the viewer's screenshot key:
//   frame.png (tonemapped), frame.exr (linear HDR), timings.json (per pass GPU and
//   CPU-record ms, min/median/max over the measured frames), trace.json (Chrome
//   trace of every frame), graph.json and graph.dot (the compiled frame graph),
//   memory.json (transient bytes, per light map and capture figures) and
//   light<i>_transmittance.png when the renderer draws light images.
// timings.json and memory.json are written from a FrameReport (capture/frame_report.h).
#include <rendergraph/vulkan/executor.h>

#include <chrono>
#include <cstdint>
#include <filesystem>
#include <functional>
#include <map>
#include <string>
#include <vector>

#include "capture/frame_report.h"
#include "capture/trace.h"

namespace avsm::gpu {
class Context;
}
namespace avsm::renderer {
class SceneRenderer;
}
namespace avsm::scene {
struct Scene;
}
namespace avsm::passes {
struct View;
}

namespace avsm::capture {

// When the steps of one frame ended on the CPU clock.
struct FrameClock {
  std::chrono::steady_clock::time_point start, built, recorded, completed;
};

// Declares one frame of `renderer` into frame slot `slot` and records it into `cmd`
// (begun and ended here, one-time submit); the clock up to `recorded`. `also_record`
// adds commands after the frame graph's (the viewer copies its light maps there).
FrameClock record_timed_frame(renderer::SceneRenderer& renderer, rg::vulkan::Executor& executor, VkCommandBuffer cmd,
                              const passes::View& view, uint32_t slot,
                              const std::function<void(VkCommandBuffer)>& also_record = {});

// One frame with nothing else in flight: recorded into slot 0, submitted, waited for,
// and its shadow counters read (finish_frame).
FrameClock render_timed_frame(gpu::Context& ctx, renderer::SceneRenderer& renderer, rg::vulkan::Executor& executor,
                              VkCommandBuffer cmd, const passes::View& view,
                              const std::function<void(VkCommandBuffer)>& also_record = {});

// Per-pass timings of the measured frames, and a trace of every frame logged.
class FrameTimingLog {
 public:
  // Trace times are in ms from `origin`.
  explicit FrameTimingLog(std::chrono::steady_clock::time_point origin = std::chrono::steady_clock::now());

  // Logs a frame that just completed (its wall time ends now), with its shadow maps'
  // figures (finish_frame()'s): always on the trace, in the statistics only when
  // `measured` (warm-up frames are not). Returns the frame's wall time in ms.
  double add_frame(const FrameClock& clock, const std::vector<rg::vulkan::PassTiming>& passes,
                   const std::vector<passes::LightShadowStats>& shadows, bool measured);

  // Forgets every frame (the viewer keeps only the frames since the last change).
  void clear();

  // One pass's samples over the measured frames.
  struct PassSamples {
    std::string name;
    rg::QueueType queue = rg::QueueType::Graphics;
    std::vector<double> gpu_ms, cpu_record_ms;
  };
  const std::vector<PassSamples>& passes() const { return passes_; }  // in the order first seen
  // Each pass's median GPU ms over the measured frames (as in timings.json), by name.
  std::map<std::string, double> median_gpu_ms() const;
  // Per measured frame: its GPU ms, wall times, shadow and inspection passes' ms, pages.
  const std::vector<FrameSample>& frames() const { return frames_; }
  const TraceWriter& trace() const { return trace_; }
  uint32_t frames_logged() const { return frames_logged_; }

 private:
  std::chrono::steady_clock::time_point origin_;
  TraceWriter trace_;
  uint32_t frames_logged_ = 0;
  std::vector<PassSamples> passes_;
  std::map<std::string, size_t> pass_index_;
  std::vector<FrameSample> frames_;
};

// Everything write_frame_outputs reads; the frame must have completed.
struct FrameOutputSources {
  gpu::Context& ctx;
  const renderer::SceneRenderer& renderer;
  const rg::vulkan::Executor& executor;
  const scene::Scene& scene;  // the scene as rendered (overrides applied)
  const FrameTimingLog& timings;
  uint64_t frames_with_capture_overflow = 0;
};

struct FrameOutputFiles {
  std::filesystem::path png, exr, timings;
  FrameReport report;  // what timings.json and memory.json were written from; no quality or probes yet
};

// The memory figures of `renderer`'s last frame, compiled as `plan`, as memory.json holds them.
MemoryReport memory_report(const rg::CompiledPlan& plan, const renderer::SceneRenderer& renderer,
                           const scene::Scene& scene, uint64_t frames_with_capture_overflow);

// Creates out_dir and writes the files listed at the top of this header.
// Throws std::runtime_error naming a file that cannot be written.
FrameOutputFiles write_frame_outputs(const std::filesystem::path& out_dir, const FrameOutputSources& frame);

}  // namespace avsm::capture
