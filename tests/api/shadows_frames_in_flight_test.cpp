// The embedding API with two frames in flight, driven as a host drives it: a command
// buffer, fence and executor per frame slot, the light moved every frame with
// set_light(), frame N+1 declared, recorded and submitted while frame N has not run
// (held on the queue by a semaphore only this test signals), under validation and
// synchronization validation (support/gpu_test.cpp). Every frame's transmittance at
// probe points on the ground, read when its own fence signalled, and its capture
// figures must be bitwise those of one frame in flight.
#include <gtest/gtest.h>

#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <chrono>
#include <cmath>
#include <condition_variable>
#include <memory>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "avsm/shadows.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "passes/shadow_probe_pass.h"
#include "support/gpu_test.h"

namespace avsm {
namespace {

using ShadowsFramesInFlightTest = testing::GpuTest;

constexpr uint32_t kFrames = 4;

// A ground quad (y = 0, x and z in [-2, 2]) and a box hovering over it (y in [1, 2]).
struct Casters {
  gpu::Buffer vertices, indices;
  ShadowCasters views;
  Bounds bounds;
};

void add_quad(std::vector<CasterVertex>& vertices, std::vector<uint32_t>& indices, const std::vector<glm::vec3>& corners) {
  const uint32_t base = uint32_t(vertices.size());
  for (const glm::vec3& c : corners) vertices.push_back({{c.x, c.y, c.z}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f}});
  for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + i);
}

Casters make_casters(const gpu::Context& ctx) {
  std::vector<CasterVertex> vertices;
  std::vector<uint32_t> indices;
  add_quad(vertices, indices, {{-2, 0, -2}, {-2, 0, 2}, {2, 0, 2}, {2, 0, -2}});
  const float lo = -0.5f, hi = 0.5f;
  for (float y : {1.0f, 2.0f}) add_quad(vertices, indices, {{lo, y, lo}, {lo, y, hi}, {hi, y, hi}, {hi, y, lo}});
  for (float x : {lo, hi}) add_quad(vertices, indices, {{x, 1, lo}, {x, 2, lo}, {x, 2, hi}, {x, 1, hi}});
  for (float z : {lo, hi}) add_quad(vertices, indices, {{lo, 1, z}, {lo, 2, z}, {hi, 2, z}, {hi, 1, z}});
  Casters casters;
  for (const CasterVertex& v : vertices) casters.bounds.extend(glm::vec3(v.position[0], v.position[1], v.position[2]));
  casters.views.meshes.draws = {{0, uint32_t(indices.size()), 0}};
  casters.vertices = gpu::create_buffer_from(ctx, std::move(vertices), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "test vertices");
  casters.indices = gpu::create_buffer_from(ctx, std::move(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "test indices");
  casters.views.meshes.vertices = casters.vertices.handle();
  casters.views.meshes.vertices_size = casters.vertices.size();
  casters.views.meshes.indices = casters.indices.handle();
  casters.views.meshes.indices_size = casters.indices.size();
  return casters;
}

// Frame `frame`'s sun: slanted, turning about the vertical, so the box's shadow sweeps
// over the ground.
Light sun_at(uint32_t frame) {
  Light sun;
  sun.name = "sun";
  sun.nodes = 4;
  sun.resolution = 32;
  const float angle = 0.5f * float(frame);
  sun.direction = glm::vec3(std::cos(angle), -1.5f, std::sin(angle));
  return sun;
}

std::vector<glm::vec3> ground_probes() {
  std::vector<glm::vec3> points;
  for (int x = -3; x <= 3; ++x)
    for (int z = -3; z <= 3; ++z) points.emplace_back(0.5f * float(x), 0.01f, 0.5f * float(z));
  return points;
}

// What one frame left for the CPU.
struct FrameResult {
  std::vector<float> transmittance;  // at ground_probes()
  uint64_t segments_captured = 0;
  bool overflowed = false;
};

// A timeline semaphore the first frame waits for on the queue: while the test holds
// it, that frame cannot run. A watchdog releases it after a while, so that a call
// which waits for the device fails the test instead of hanging it.
class QueueGate {
 public:
  explicit QueueGate(VkDevice device) : device_(device) {
    VkSemaphoreTypeCreateInfo type{VK_STRUCTURE_TYPE_SEMAPHORE_TYPE_CREATE_INFO};
    type.semaphoreType = VK_SEMAPHORE_TYPE_TIMELINE;
    VkSemaphoreCreateInfo info{VK_STRUCTURE_TYPE_SEMAPHORE_CREATE_INFO, &type};
    vkCreateSemaphore(device_, &info, nullptr, &semaphore_);
    watchdog_ = std::thread([this] {
      std::unique_lock lock(mutex_);
      if (!released_.wait_for(lock, std::chrono::seconds(30), [this] { return opened_; })) {
        timed_out_ = true;
        open_locked();
      }
    });
  }
  ~QueueGate() {
    open();
    watchdog_.join();
    vkDestroySemaphore(device_, semaphore_, nullptr);
  }
  VkSemaphore semaphore() const { return semaphore_; }
  void open() {
    std::lock_guard lock(mutex_);
    open_locked();
    released_.notify_all();
  }
  bool timed_out() {
    std::lock_guard lock(mutex_);
    return timed_out_;
  }

 private:
  void open_locked() {
    if (opened_) return;
    opened_ = true;
    VkSemaphoreSignalInfo signal{VK_STRUCTURE_TYPE_SEMAPHORE_SIGNAL_INFO};
    signal.semaphore = semaphore_;
    signal.value = 1;
    vkSignalSemaphore(device_, &signal);
  }
  VkDevice device_;
  VkSemaphore semaphore_ = VK_NULL_HANDLE;
  std::mutex mutex_;
  std::condition_variable released_;
  bool opened_ = false, timed_out_ = false;
  std::thread watchdog_;
};

// The host's side of a frame slot.
struct HostSlot {
  VkCommandBuffer cmd = VK_NULL_HANDLE;
  VkFence fence = VK_NULL_HANDLE;
  std::unique_ptr<rg::vulkan::Executor> executor;
  int frame = -1;  // the frame in flight in it; -1: none
};

struct Sequence {
  std::vector<FrameResult> frames = std::vector<FrameResult>(kFrames);
  bool second_recorded_while_first_waited = false;  // two in flight: frame 1 submitted before frame 0 ran
  bool gate_timed_out = false;
};

// Renders kFrames frames, the sun moving, with `in_flight` frames in flight.
Sequence render(gpu::Context& ctx, Shadows& shadows, passes::ShadowProbePass& probes, const Casters& casters,
           uint32_t in_flight) {
  shadows.set_frames_in_flight(in_flight);
  probes.set_frames_in_flight(in_flight);
  std::vector<HostSlot> slots(in_flight);
  for (HostSlot& slot : slots) {
    slot.cmd = ctx.allocate_command_buffer("test frame");
    VkFenceCreateInfo fence_info{VK_STRUCTURE_TYPE_FENCE_CREATE_INFO};
    vkCreateFence(ctx.device(), &fence_info, nullptr, &slot.fence);
    slot.executor = std::make_unique<rg::vulkan::Executor>(ctx, gpu::TimestampMode::Exact);
  }
  Sequence run;
  auto finish = [&](uint32_t index) {
    HostSlot& slot = slots[index];
    vkWaitForFences(ctx.device(), 1, &slot.fence, VK_TRUE, UINT64_MAX);
    vkResetFences(ctx.device(), 1, &slot.fence);
    FrameResult& result = run.frames[slot.frame];
    const std::vector<LightStats> stats = shadows.finish_frame(index);
    result.segments_captured = stats.at(0).segments_captured;
    result.overflowed = stats.at(0).overflowed;
    result.transmittance = probes.results(index).at(0);
    slot.frame = -1;
  };
  QueueGate gate(ctx.device());
  const Camera camera;
  for (uint32_t frame = 0; frame < kFrames; ++frame) {
    const uint32_t index = frame % in_flight;
    HostSlot& slot = slots[index];
    if (slot.frame >= 0) finish(index);
    shadows.set_light(sun_at(frame), casters.bounds);  // only moves it: no wait for the frames in flight
    rg::Graph graph;
    probes.add_to_graph(graph, shadows.add_to_graph(graph, camera, casters.views, index));
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    vkBeginCommandBuffer(slot.cmd, &begin);
    slot.executor->record(graph, slot.cmd);
    vkEndCommandBuffer(slot.cmd);
    // With two in flight, frame 0 waits on the queue until frame 1 is submitted.
    const bool held = in_flight > 1 && frame == 0;
    VkCommandBufferSubmitInfo cmd_info{VK_STRUCTURE_TYPE_COMMAND_BUFFER_SUBMIT_INFO};
    cmd_info.commandBuffer = slot.cmd;
    VkSemaphoreSubmitInfo wait{VK_STRUCTURE_TYPE_SEMAPHORE_SUBMIT_INFO};
    wait.semaphore = gate.semaphore();
    wait.value = 1;
    wait.stageMask = VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT;
    VkSubmitInfo2 submit{VK_STRUCTURE_TYPE_SUBMIT_INFO_2};
    submit.commandBufferInfoCount = 1;
    submit.pCommandBufferInfos = &cmd_info;
    submit.waitSemaphoreInfoCount = held ? 1 : 0;
    submit.pWaitSemaphoreInfos = &wait;
    EXPECT_EQ(vkQueueSubmit2(ctx.graphics_queue().handle, 1, &submit, slot.fence), VK_SUCCESS);
    slot.frame = int(frame);
    if (in_flight > 1 && frame == 1) {
      run.second_recorded_while_first_waited = vkGetFenceStatus(ctx.device(), slots[0].fence) == VK_NOT_READY;
      run.gate_timed_out = gate.timed_out();
      gate.open();
    }
  }
  // The frames still in flight, oldest first.
  for (uint32_t i = 0; i < in_flight; ++i) {
    const uint32_t index = (kFrames + i) % in_flight;
    if (slots[index].frame >= 0) finish(index);
  }
  for (HostSlot& slot : slots) {
    vkDestroyFence(ctx.device(), slot.fence, nullptr);
    vkFreeCommandBuffers(ctx.device(), ctx.command_pool(), 1, &slot.cmd);
  }
  return run;
}

TEST_F(ShadowsFramesInFlightTest, TwoFramesInFlightGiveTheFramesOfOne) {
  Shadows shadows(ctx(), ShaderLocation::of_package());
  const Casters casters = make_casters(ctx());
  passes::ShadowProbePass probes(ctx(), shaders());
  probes.set_points(ground_probes(), 1);
  const Sequence one = render(ctx(), shadows, probes, casters, 1);
  const Sequence two = render(ctx(), shadows, probes, casters, 2);

  EXPECT_FALSE(two.gate_timed_out) << "set_light or add_to_graph waited for the frame in flight";
  EXPECT_TRUE(two.second_recorded_while_first_waited);
  for (uint32_t frame = 0; frame < kFrames; ++frame) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    const FrameResult &a = one.frames[frame], &b = two.frames[frame];
    ASSERT_EQ(a.transmittance.size(), ground_probes().size());
    EXPECT_FALSE(a.overflowed);
    EXPECT_GT(a.segments_captured, 0u);
    EXPECT_EQ(a.transmittance, b.transmittance);  // bitwise: the same floats
    EXPECT_EQ(a.segments_captured, b.segments_captured);
  }
  // Not vacuous: the box's shadow moves over the probes, so each frame's results are its
  // own (a frame reading another slot's parameters or results would not match), and
  // part of the ground is in shadow, part lit.
  for (uint32_t frame = 1; frame < kFrames; ++frame) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    EXPECT_NE(one.frames[frame].transmittance, one.frames[frame - 1].transmittance);
  }
  const std::vector<float>& first = one.frames[0].transmittance;
  EXPECT_LT(*std::min_element(first.begin(), first.end()), 0.1f);
  EXPECT_GT(*std::max_element(first.begin(), first.end()), 0.9f);
}

}  // namespace
}  // namespace avsm
