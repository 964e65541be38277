// Frames in flight (passes/frame/frames_in_flight.h, renderer/frame_slots.h): the default
// scene with its spot light moving, rendered with one frame in flight (submit and wait,
// as before) and with two (frame N+1 recorded and submitted while frame N runs), under
// validation + synchronization validation (support/gpu_test.cpp). Every frame's image,
// probes and capture figures must be the same in both runs, each read when its own
// frame's fence signalled.
#include <gtest/gtest.h>

#include <rendergraph/vulkan/executor.h>

#include <chrono>
#include <cmath>
#include <cstring>
#include <iostream>
#include <vector>

#include "passes/shadows/shadow_settings.h"
#include "capture/frame_outputs.h"
#include "gpu/barriers.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "passes/frame/view.h"
#include "renderer/frame_slots.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"
#include "support/gpu_test.h"

namespace avsm {
namespace frames_in_flight_test {  // one per file: test targets are unity builds
namespace {

using FramesInFlightTest = testing::GpuTest;

constexpr uint32_t kWidth = 160, kHeight = 90;
constexpr uint32_t kMovingLight = 1;  // the default scene's spot light
constexpr uint32_t kFrames = 3;

// What one frame left for the CPU.
struct FrameResult {
  std::vector<uint8_t> pixels;               // the tonemapped image, RGBA8
  std::vector<std::vector<float>> probes;    // [light][point]
  std::vector<uint64_t> segments_requested;  // per light, from its capture counters
  bool overflowed = false;
};

scene::Scene small_default_scene() {
  scene::Scene scene = scene::load_scene(AVSM_DEFAULT_SCENE);
  // Dense 64^2 maps (the default scene's are paged), as --shadow-res 64 gives.
  for (scene::Light& light : scene.lights) passes::apply_shadow_overrides({.resolution = 64}, light);
  return scene;
}

// Frame `frame`'s spot light: circling the scene's centre about the vertical, aimed at it.
void place_moving_light(renderer::SceneRenderer& renderer, const scene::Scene& scene, uint32_t frame) {
  const glm::vec3 target = scene.bounds.center();
  const glm::vec3 offset = scene.lights[kMovingLight].position - target;
  const float angle = 0.4f * float(frame);
  const glm::vec3 turned(offset.x * std::cos(angle) - offset.z * std::sin(angle), offset.y,
                         offset.x * std::sin(angle) + offset.z * std::cos(angle));
  renderer.place_light(kMovingLight, target + turned, -turned);
}

struct Sequence {
  std::vector<FrameResult> frames;
  double ms_per_frame = 0;
};

// Probes just above the floor, on a grid across the scene: the moving light's shadows
// sweep over some of them.
std::vector<glm::vec3> floor_probes(const scene::Scene& scene) {
  std::vector<glm::vec3> points;
  const glm::vec3 centre = scene.bounds.center(), half = 0.5f * (scene.bounds.max - scene.bounds.min);
  for (int x = -3; x <= 3; ++x)
    for (int z = -3; z <= 3; ++z)
      points.emplace_back(centre.x + half.x * float(x) / 4.0f, scene.bounds.min.y + 0.02f,
                          centre.z + half.z * float(z) / 4.0f);
  return points;
}

// Renders the moving-light sequence with `in_flight` frames in flight, after warm-up
// frames (all finished) that grow the capture buffers to what the scene needs.
Sequence render_sequence(gpu::Context& ctx, renderer::SceneRenderer& renderer, const scene::Scene& scene,
                         uint32_t in_flight) {
  renderer.set_frames_in_flight(in_flight);
  const passes::View view = passes::make_view(scene.cameras.front(), kWidth, kHeight);
  renderer::FrameSlots slots(ctx, gpu::TimestampMode::Exact, in_flight);
  // Each slot's frame copies its image here (after its graph), read when its fence signals.
  std::vector<gpu::Buffer> readbacks;
  for (uint32_t i = 0; i < in_flight; ++i)
    readbacks.push_back(gpu::Buffer::create(ctx, {uint64_t(kWidth) * kHeight * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                  gpu::MemoryLocation::HostReadback, "frame readback"}));
  std::vector<int> slot_frame(in_flight, -1);
  Sequence sequence;
  sequence.frames.resize(kFrames);
  bool grew = false;
  auto finished = [&](renderer::FrameSlots::Slot& slot) {
    renderer.finish_frame(slot.index);
    grew = false;
    FrameResult result;
    for (const passes::LightShadowStats& light : renderer.shadows().frame_stats()) {
      result.segments_requested.push_back(light.capture_requested);
      result.overflowed = result.overflowed || light.lost_shadowing();
      grew = grew || light.grew;
    }
    result.probes = renderer.probe_results();
    const auto* bytes = static_cast<const uint8_t*>(readbacks[slot.index].mapped());
    result.pixels.assign(bytes, bytes + readbacks[slot.index].size());
    if (slot_frame[slot.index] >= 0) sequence.frames[slot_frame[slot.index]] = std::move(result);
  };
  auto submit = [&](int frame) {
    renderer::FrameSlots::Slot& slot = slots.acquire(finished);
    slot_frame[slot.index] = frame;
    place_moving_light(renderer, scene, frame < 0 ? 0 : uint32_t(frame));
    capture::record_timed_frame(renderer, *slot.executor, slot.cmd, view, slot.index, [&](VkCommandBuffer cmd) {
      gpu::record_image_readback(cmd, renderer.ldr(), renderer::SceneRenderer::kOutputLayout, readbacks[slot.index]);
    });
    slots.submit(slot);
  };
  // Warm-up: until the capture buffers stop growing (a few frames at most).
  for (int warm_up = 0; warm_up == 0 || (grew && warm_up < 4); ++warm_up) {
    submit(-1);
    slots.finish_all(finished);
  }
  const auto start = std::chrono::steady_clock::now();
  for (uint32_t frame = 0; frame < kFrames; ++frame) submit(int(frame));
  slots.finish_all(finished);
  sequence.ms_per_frame =
      std::chrono::duration<double, std::milli>(std::chrono::steady_clock::now() - start).count() / kFrames;
  return sequence;
}

// One renderer for both runs (building its pipelines is most of the test's time); each
// run starts from warm-up frames.
TEST_F(FramesInFlightTest, TwoFramesInFlightRenderTheSameFramesAsOne) {
  const scene::Scene scene = small_default_scene();
  renderer::SceneRenderer renderer(ctx(), shaders(), scene, kWidth, kHeight);
  renderer.set_probes(floor_probes(scene));
  const Sequence one = render_sequence(ctx(), renderer, scene, 1);
  const Sequence two = render_sequence(ctx(), renderer, scene, 2);
  std::cout << "[ in flight ] " << kFrames << " frames " << kWidth << "x" << kHeight << ", shadow res 64: "
            << one.ms_per_frame << " ms per frame with 1 in flight, " << two.ms_per_frame << " with 2\n";
  for (uint32_t frame = 0; frame < kFrames; ++frame) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    const FrameResult &a = one.frames[frame], &b = two.frames[frame];
    ASSERT_FALSE(a.pixels.empty());
    // Growth mid-sequence would give the frames in flight a smaller capture than one
    // frame at a time has: a legitimate difference, which the warm-up rules out.
    EXPECT_FALSE(a.overflowed);
    EXPECT_FALSE(b.overflowed);
    EXPECT_TRUE(a.pixels == b.pixels) << "the images differ";
    EXPECT_EQ(a.probes, b.probes);
    EXPECT_EQ(a.segments_requested, b.segments_requested);
  }
  // Not vacuous: the light moves, so every frame's figures and image are its own (a
  // result read from another frame's slot would not match).
  for (uint32_t frame = 1; frame < kFrames; ++frame) {
    SCOPED_TRACE("frame " + std::to_string(frame));
    EXPECT_NE(one.frames[frame].segments_requested[kMovingLight], one.frames[frame - 1].segments_requested[kMovingLight]);
    EXPECT_NE(one.frames[frame].probes, one.frames[frame - 1].probes);
    EXPECT_FALSE(one.frames[frame].pixels == one.frames[frame - 1].pixels);
  }

  // Counts outside 1..3, and slots beyond the count, are refused.
  EXPECT_THROW(renderer.set_frames_in_flight(0), std::invalid_argument);
  EXPECT_THROW(renderer.set_frames_in_flight(4), std::invalid_argument);
  EXPECT_THROW(renderer.build_frame(passes::make_view(scene.cameras.front(), kWidth, kHeight), 2),
               std::invalid_argument);
}

}  // namespace
}  // namespace frames_in_flight_test
}  // namespace avsm
