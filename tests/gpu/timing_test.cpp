#include <gtest/gtest.h>

#include <algorithm>
#include <chrono>

#include "gpu/barriers.h"
#include "gpu/gpu_timer.h"
#include "gpu/pipeline.h"
#include "gpu/rendering.h"
#include "gpu/resources.h"
#include "support/gpu_test.h"
#include "shared/gpu/spin.h"

namespace avsm {
namespace timing_test {  // one per file: test targets are unity builds
namespace {

using testing::GpuTest;

using shared::SpinPush;

constexpr uint32_t kInvocations = 1u << 14;

// Finds an iteration count K for which one spin dispatch takes about `target_ms`
// on this device, so the test is meaningful on lavapipe and on a fast GPU alike.
uint32_t iterations_for(gpu::Context& ctx, const gpu::Pipeline& spin, const gpu::Buffer& values, double target_ms) {
  for (uint32_t iterations = 1024;; iterations *= 2) {
    auto start = std::chrono::steady_clock::now();
    ctx.submit_and_wait([&](VkCommandBuffer cmd) {
      spin.bind(cmd);
      gpu::Bindings(ctx, spin).buffer("Values", values).push(cmd);
      spin.push_constants(cmd, SpinPush{iterations, kInvocations});
      spin.dispatch_threads(cmd, kInvocations);
    });
    double ms = std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count();
    if (ms >= target_ms || iterations >= (1u << 26)) return iterations;
  }
}

// Times one frame with a K-iteration pass and a 2K-iteration pass, in the given order.
// Returns (time of K, time of 2K).
std::pair<double, double> time_k_and_2k(gpu::Context& ctx, const gpu::Pipeline& spin, const gpu::Buffer& values,
                                        const gpu::Image& target, gpu::TimestampMode mode, uint32_t k, bool k_first) {
  gpu::GpuTimer timer(ctx, 4, mode);
  std::vector<uint32_t> order = k_first ? std::vector<uint32_t>{k, 2 * k} : std::vector<uint32_t>{2 * k, k};
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    gpu::clear_with_rendering(cmd, target);  // like a real frame, where graphics work precedes compute
    timer.begin_frame(cmd, uint32_t(order.size()));
    for (uint32_t iterations : order) {
      uint32_t scope = timer.begin_scope(cmd, "spin " + std::to_string(iterations));
      spin.bind(cmd);
      gpu::Bindings(ctx, spin).buffer("Values", values).push(cmd);
      spin.push_constants(cmd, SpinPush{iterations, kInvocations});
      spin.dispatch_threads(cmd, kInvocations);
      timer.end_scope(cmd, scope);
      // Both dispatches write `values`: order them like the frame graph would.
      gpu::memory_barrier(cmd, gpu::kComputeWrite, gpu::kComputeWrite);
    }
  });
  std::vector<gpu::ScopeTiming> t = timer.read_scopes();
  return k_first ? std::pair(t[0].gpu_ms, t[1].gpu_ms) : std::pair(t[1].gpu_ms, t[0].gpu_ms);
}

TEST_F(GpuTest, CalibrationDetectsLateComputeTimestamps) {
  gpu::TimestampCalibration calibration = gpu::calibrate_timestamps(ctx(), shaders());
  std::printf("timestamps: mode %s, dispatch %.3f ms by timestamps, %.3f ms by host clock\n",
              gpu::to_string(calibration.mode), calibration.dispatch_ms_timestamps, calibration.dispatch_ms_host);
  if (ctx().info().is_lavapipe()) {
    // Measured on lavapipe: begin/end timestamps around a dispatch see almost none of it.
    EXPECT_EQ(calibration.mode, gpu::TimestampMode::EndToEnd);
    EXPECT_LT(calibration.dispatch_ms_timestamps, 0.25 * calibration.dispatch_ms_host);
  } else {
    EXPECT_EQ(calibration.mode, gpu::TimestampMode::Exact);
  }
}

TEST_F(GpuTest, PassesOfKnownCostAreTimedInRatio) {
  gpu::TimestampCalibration calibration = gpu::calibrate_timestamps(ctx(), shaders());
  gpu::Buffer values = gpu::Buffer::create(ctx(), {kInvocations * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
                                                   gpu::MemoryLocation::DeviceLocal, "spin values"});
  gpu::Pipeline spin = gpu::Pipeline::compute(ctx(), shaders().load("shaders/gpu/spin.comp"), "spin");
  gpu::ImageDesc target_desc;
  target_desc.width = target_desc.height = 64;
  target_desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT;
  target_desc.name = "timing test target";
  gpu::Image target = gpu::Image::create(ctx(), target_desc);
  uint32_t k = iterations_for(ctx(), spin, values, 15.0);

  // Median over frames, alternating which pass goes first: one frame can hiccup
  // (other processes on the machine), and a bias of the first or second slot cancels.
  std::vector<double> ratios;
  for (int frame = 0; frame < 6; ++frame) {
    auto [k_ms, two_k_ms] = time_k_and_2k(ctx(), spin, values, target, calibration.mode, k, frame % 2 == 0);
    ASSERT_GT(k_ms, 0.0);
    std::printf("K: %.3f ms, 2K: %.3f ms (mode %s)\n", k_ms, two_k_ms, gpu::to_string(calibration.mode));
    ratios.push_back(two_k_ms / k_ms);
  }
  std::sort(ratios.begin(), ratios.end());
  double median = 0.5 * (ratios[2] + ratios[3]);
  EXPECT_NEAR(median, 2.0, 0.4) << "2K iterations should take twice as long as K";
}

}  // namespace
}  // namespace timing_test
}  // namespace avsm
