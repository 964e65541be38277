// The embedding API with two frames in flight, driven as a host drives it: a command
// buffer, fence and executor per frame slot (renderer::FrameSlots), the light moved every frame with
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
#include <iostream>
#include <mutex>
#include <string>
#include <thread>
#include <vector>

#include "avsm/shadows.h"
#include "avsm/shadows_rendergraph.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "passes/shadows/shadow_maps.h"
#include "passes/shadows/inspection/shadow_probe_pass.h"
#include "renderer/frame_slots.h"
#include "support/gpu_test.h"

namespace avsm {
namespace shadows_frames_in_flight_test {  // one per file: test targets are unity builds
namespace {

using ShadowsFramesInFlightTest = testing::GpuTest;

constexpr uint32_t kFrames = 4;

struct Casters {
  gpu::Buffer vertices, indices;
  ShadowCasters views;
  Bounds bounds;
};

using Quad = std::vector<glm::vec3>;  // 4 corners

// Quads as mesh casters, one draw.
Casters make_casters(const gpu::Context& ctx, const std::vector<Quad>& quads) {
  std::vector<CasterVertex> vertices;
  std::vector<uint32_t> indices;
  Casters casters;
  for (const Quad& quad : quads) {
    const uint32_t base = uint32_t(vertices.size());
    for (const glm::vec3& c : quad) {
      vertices.push_back({{c.x, c.y, c.z}, {0.0f, 1.0f, 0.0f}, {0.0f, 0.0f}});
      casters.bounds.extend(c);
    }
    for (uint32_t i : {0u, 1u, 2u, 0u, 2u, 3u}) indices.push_back(base + i);
  }
  casters.views.meshes.draws = {{0, uint32_t(indices.size()), 0}};
  casters.vertices = gpu::create_buffer_from(ctx, std::move(vertices), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "test vertices");
  casters.indices = gpu::create_buffer_from(ctx, std::move(indices), VK_BUFFER_USAGE_INDEX_BUFFER_BIT, "test indices");
  casters.views.meshes.vertices = casters.vertices.handle();
  casters.views.meshes.vertices_size = casters.vertices.size();
  casters.views.meshes.indices = casters.indices.handle();
  casters.views.meshes.indices_size = casters.indices.size();
  return casters;
}

Quad level_quad(float y, float lo, float hi) { return {{lo, y, lo}, {lo, y, hi}, {hi, y, hi}, {hi, y, lo}}; }

// A ground quad (y = 0, x and z in [-2, 2]) and a box hovering over it (y in [1, 2]).
std::vector<Quad> ground_and_box() {
  const float lo = -0.5f, hi = 0.5f;
  std::vector<Quad> quads = {level_quad(0.0f, -2.0f, 2.0f), level_quad(1.0f, lo, hi), level_quad(2.0f, lo, hi)};
  for (float x : {lo, hi}) quads.push_back({{x, 1, lo}, {x, 2, lo}, {x, 2, hi}, {x, 1, hi}});
  for (float z : {lo, hi}) quads.push_back({{lo, 1, z}, {lo, 2, z}, {hi, 2, z}, {hi, 1, z}});
  return quads;
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

void record(const rg::Graph& graph, rg::vulkan::Executor& executor, VkCommandBuffer cmd) {
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
  vkBeginCommandBuffer(cmd, &begin);
  executor.record(graph, cmd);
  vkEndCommandBuffer(cmd);
}

struct Sequence {
  std::vector<FrameResult> frames = std::vector<FrameResult>(kFrames);
  bool second_recorded_while_first_waited = false;  // two in flight: frame 1 submitted before frame 0 ran
  bool gate_timed_out = false;
};

// Renders kFrames frames, the sun moving, with `in_flight` frames in flight: a command
// buffer, fence and executor per slot (renderer::FrameSlots), each slot's frame finished
// when its fence signalled.
Sequence render(gpu::Context& ctx, Shadows& shadows, passes::ShadowProbePass& probes, const Casters& casters,
                uint32_t in_flight) {
  shadows.set_frames_in_flight(in_flight);
  probes.set_frames_in_flight(in_flight);
  renderer::FrameSlots slots(ctx, gpu::TimestampMode::Exact, in_flight);
  std::vector<uint32_t> slot_frame(in_flight);
  Sequence run;
  auto finished = [&](renderer::FrameSlots::Slot& slot) {
    FrameResult& result = run.frames[slot_frame[slot.index]];
    const std::vector<LightStats> stats = shadows.finish_frame(slot.index);
    result.segments_captured = stats.at(0).segments_captured;
    result.overflowed = stats.at(0).overflowed;
    result.transmittance = probes.results(slot.index).at(0);
  };
  QueueGate gate(ctx.device());
  const renderer::FrameSlots::Slot* first = nullptr;
  const Camera camera;
  for (uint32_t frame = 0; frame < kFrames; ++frame) {
    renderer::FrameSlots::Slot& slot = slots.acquire(finished);
    slot_frame[slot.index] = frame;
    shadows.set_light(sun_at(frame), casters.bounds);  // only moves it: no wait for the frames in flight
    rg::Graph graph;
    passes::ShadowInputs inputs = avsm::add_to_graph(graph, shadows, camera, casters.views, slot.index);
    probes.add_to_graph(graph, inputs);
    record(graph, *slot.executor, slot.cmd);
    // With two in flight, frame 0 waits on the queue until frame 1 is submitted.
    if (in_flight > 1 && frame == 0) {
      slots.submit(slot, gate.semaphore(), VK_PIPELINE_STAGE_2_ALL_COMMANDS_BIT, VK_NULL_HANDLE, 1);
      first = &slot;
    } else {
      slots.submit(slot);
    }
    if (first && frame == 1) {
      run.second_recorded_while_first_waited = vkGetFenceStatus(ctx.device(), first->fence) == VK_NOT_READY;
      run.gate_timed_out = gate.timed_out();
      gate.open();
    }
  }
  slots.finish_all(finished);
  return run;
}

TEST_F(ShadowsFramesInFlightTest, TwoFramesInFlightGiveTheFramesOfOne) {
  Shadows shadows(ctx(), ShaderLocation::of_package());
  const Casters casters = make_casters(ctx(), ground_and_box());
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

// Capture growth that makes buffers again while the next frame is in flight. The API's
// lights are AVSM, whose growth replaces no buffer (the capture lists are per frame);
// the exact lists that lookups read (technique "uncompressed", the renderer's exact
// reference) are buffers sized by the capture, so this drives passes::ShadowMaps, which
// the API wraps. The frame in flight keeps the old lists until it finishes, with no wait
// for the device (freed at once instead, they are written after their memory is gone:
// this test then crashes on lavapipe). 24 quads over half the texels ask for more than the first guess (8 a texel).
TEST_F(ShadowsFramesInFlightTest, GrowthWhileAFrameIsInFlightKeepsItsBuffers) {
  std::vector<Quad> stack;
  for (int i = 0; i < 24; ++i) stack.push_back(level_quad(0.05f * float(i), -1.0f, 1.0f));
  const Casters casters = make_casters(ctx(), stack);
  scene::Light light;
  light.direction = glm::normalize(glm::vec3(0.2f, -1.0f, 0.1f));
  light.shadow.technique = "uncompressed";
  light.shadow.resolution = 16;
  passes::ShadowMaps maps(ctx(), shaders());
  maps.set_lights({light}, casters.bounds);
  maps.set_frames_in_flight(2);
  renderer::FrameSlots slots(ctx(), gpu::TimestampMode::Exact, 2);
  std::vector<passes::LightShadowStats> stats;  // per frame, in order
  // Frame 0 finishes when frame 2 needs its slot: frame 1 is in flight then.
  auto finished = [&](renderer::FrameSlots::Slot& slot) {
    maps.finish_frame(slot.index);
    stats.push_back(maps.frame_stats().at(0));
  };
  for (int frame = 0; frame < 4; ++frame) {
    renderer::FrameSlots::Slot& slot = slots.acquire(finished);
    rg::Graph graph;
    maps.add_to_graph(graph, passes::View(), casters.views, slot.index);
    record(graph, *slot.executor, slot.cmd);
    slots.submit(slot);
  }
  slots.finish_all(finished);
  ASSERT_EQ(stats.size(), 4u);
  std::cout << "[ growth ] frame 0 asked for " << stats[0].capture_requested << " segments with room for "
            << stats[0].capture_capacity << "; frame 2 had room for " << stats[2].capture_capacity << "\n";
  EXPECT_TRUE(stats[0].overflowed && stats[0].grew) << "frame 0 should overflow the first guess and grow the lists";
  EXPECT_FALSE(stats[2].overflowed);
  EXPECT_EQ(stats[2].capture_requested, stats[0].capture_requested);  // every segment, in the grown lists
}

}  // namespace
}  // namespace shadows_frames_in_flight_test
}  // namespace avsm
