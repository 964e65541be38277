// Volume sequences on the GPU (renderer/volume_sequence_player.h, SceneRenderer::
// show_volume_frame, VolumePass::stream): the generated plume sequence played with two
// frames in flight, each new frame staged in its slot and copied in by the frame itself,
// must look as the same frame loaded whole by a new renderer; under validation and
// synchronization validation (support/gpu_test.cpp). And the player: frames read ahead
// into a bounded cache, a broken frame named by file and frame, the last good one kept.
#include <gtest/gtest.h>
#include <gmock/gmock.h>

#include <rendergraph/vulkan/executor.h>

#include <chrono>
#include <cstdlib>
#include <fstream>
#include <thread>
#include <vector>

#include "capture/frame_outputs.h"
#include "gpu/barriers.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "passes/frame/view.h"
#include "renderer/frame_slots.h"
#include "renderer/scene_renderer.h"
#include "renderer/volume_sequence_player.h"
#include "scene/scene.h"
#include "support/gpu_test.h"

namespace avsm {
namespace volume_sequence_test {  // one per file: test targets are unity builds
namespace {

using VolumeSequenceTest = testing::GpuTest;
using ::testing::AllOf;
using ::testing::HasSubstr;

constexpr uint32_t kWidth = 128, kHeight = 72;

std::filesystem::path sequence_scene_file() {
  return std::filesystem::path(AVSM_DEFAULT_SCENE).parent_path() / "plume_sequence.scene.json";
}

scene::Scene small_sequence_scene() {
  scene::Scene scene = scene::load_scene(sequence_scene_file());
  for (scene::Light& light : scene.lights) light.shadow.resolution = 64;
  return scene;
}

float time_of(const scene::VolumeSequence& sequence, int frame) {
  return float(frame - sequence.timing.offset) / sequence.timing.fps;
}

// Renders `frames` (times) one after another with two frames in flight, each frame twice
// (the second is kept: the first grows any capture buffer the new smoke needs), calling
// `before(frame)` before each is declared. Returns each kept frame's tonemapped image.
std::vector<std::vector<uint8_t>> render_frames(gpu::Context& ctx, renderer::SceneRenderer& renderer,
                                                const passes::View& view, std::size_t frames,
                                                const std::function<void(std::size_t)>& before) {
  renderer.set_frames_in_flight(2);
  renderer::FrameSlots slots(ctx, gpu::TimestampMode::Exact, 2);
  std::vector<gpu::Buffer> readbacks;
  for (uint32_t i = 0; i < 2; ++i)
    readbacks.push_back(gpu::Buffer::create(ctx, {uint64_t(kWidth) * kHeight * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                  gpu::MemoryLocation::HostReadback, "frame readback"}));
  std::vector<int> slot_frame(2, -1);
  std::vector<std::vector<uint8_t>> images(frames);
  const auto finished = [&](renderer::FrameSlots::Slot& slot) {
    renderer.finish_frame(slot.index);
    const auto* bytes = static_cast<const uint8_t*>(readbacks[slot.index].mapped());
    if (slot_frame[slot.index] >= 0) images[std::size_t(slot_frame[slot.index])].assign(bytes, bytes + readbacks[slot.index].size());
  };
  for (std::size_t frame = 0; frame < frames; ++frame) {
    before(frame);
    for (int render = 0; render < 2; ++render) {
      renderer::FrameSlots::Slot& slot = slots.acquire(finished);
      slot_frame[slot.index] = render == 1 ? int(frame) : -1;
      capture::record_timed_frame(renderer, *slot.executor, slot.cmd, view, slot.index, [&](VkCommandBuffer cmd) {
        gpu::record_image_readback(cmd, renderer.ldr(), renderer::SceneRenderer::kOutputLayout, readbacks[slot.index]);
      });
      slots.submit(slot);
    }
  }
  slots.finish_all(finished);
  return images;
}

int largest_difference(const std::vector<uint8_t>& a, const std::vector<uint8_t>& b) {
  int largest = 0;
  for (std::size_t i = 0; i < a.size(); ++i) largest = std::max(largest, std::abs(int(a[i]) - int(b[i])));
  return largest;
}

TEST_F(VolumeSequenceTest, StreamedFramesLookAsTheFramesLoadedWhole) {
  const scene::Scene scene = small_sequence_scene();
  ASSERT_EQ(scene.volume_sequences.size(), 1u);
  const scene::VolumeSequence& sequence = scene.volume_sequences[0];
  const passes::View view = passes::make_view(scene.cameras.front(), kWidth, kHeight);
  // Forward, a jump ahead to a larger frame (the buffers grow), back to a smaller one.
  const std::vector<int> frames{2, 3, 20, 6};

  renderer::SceneRenderer streamed(ctx(), shaders(), scene, kWidth, kHeight);
  renderer::VolumeSequencePlayer player(scene.volume_sequences, ctx().info().max_image_dimension_3d);
  const std::vector<std::vector<uint8_t>> played = render_frames(ctx(), streamed, view, frames.size(), [&](std::size_t i) {
    const auto shown = player.at(time_of(sequence, frames[i]), /*wait=*/true);
    ASSERT_EQ(shown.size(), 1u);
    EXPECT_EQ(shown[0].frame, frames[i]);
    streamed.show_volume_frame(shown[0].volume, shown[0].part);
  });
  // Both ways in: buffers made anew for a frame larger than any before (20 at least), and
  // staged in a slot when it fits (6 at least, after 20).
  EXPECT_EQ(streamed.volume_stream_stats().frames, frames.size());
  EXPECT_GE(streamed.volume_stream_stats().reallocations, 1u);
  EXPECT_LT(streamed.volume_stream_stats().reallocations, frames.size());

  std::vector<std::vector<uint8_t>> loaded;
  for (int frame : frames) {
    scene::Scene whole = scene;
    whole.volumes[0] = sequence.load_frame(frame);
    renderer::SceneRenderer fresh(ctx(), shaders(), whole, kWidth, kHeight);
    loaded.push_back(render_frames(ctx(), fresh, view, 1, [](std::size_t) {})[0]);
  }
  for (std::size_t i = 0; i < frames.size(); ++i) {
    SCOPED_TRACE("frame " + std::to_string(frames[i]));
    ASSERT_FALSE(played[i].empty());
    EXPECT_LE(largest_difference(played[i], loaded[i]), 1);
  }
  // Not vacuous: the smoke moves, so each frame's image is its own.
  for (std::size_t i = 1; i < frames.size(); ++i) EXPECT_GT(largest_difference(played[i], played[i - 1]), 4);
}

// The generated sequence copied, with frame 6 cut short as a crashed write leaves it.
struct BrokenCopy {
  std::filesystem::path dir = std::filesystem::temp_directory_path() / ("avsm_broken_sequence_" + std::to_string(::getpid()));
  BrokenCopy() {
    std::filesystem::create_directories(dir / "plume_sequence");
    const std::filesystem::path source = sequence_scene_file().parent_path();
    std::filesystem::copy(source / "plume_sequence", dir / "plume_sequence",
                          std::filesystem::copy_options::recursive | std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(source / "plume_sequence.scene.json", dir / "scene.json", std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(source / "stage.gltf", dir / "stage.gltf", std::filesystem::copy_options::overwrite_existing);
    std::filesystem::copy_file(source / "stage.bin", dir / "stage.bin", std::filesystem::copy_options::overwrite_existing);
  }
  void break_frame(int frame) const {
    char name[32];
    std::snprintf(name, sizeof name, "plume.%04d.vdb", frame);
    const std::filesystem::path file = dir / "plume_sequence" / name;
    std::filesystem::resize_file(file, std::filesystem::file_size(file) / 2);
  }
  ~BrokenCopy() {
    std::error_code ignored;
    std::filesystem::remove_all(dir, ignored);
  }
};

TEST_F(VolumeSequenceTest, ThePlayerReadsAheadIntoABoundedCacheAndNamesABrokenFrame) {
  BrokenCopy copy;
  const scene::Scene scene = scene::load_scene(copy.dir / "scene.json");
  copy.break_frame(6);  // after loading: as a cache still being written when playing starts
  const scene::VolumeSequence& sequence = scene.volume_sequences[0];
  renderer::SequencePlayerOptions options;
  options.read_ahead = 3;
  options.cache_frames = 5;
  renderer::VolumeSequencePlayer player(scene.volume_sequences, ctx().info().max_image_dimension_3d, options);

  auto shown = player.at(time_of(sequence, 1), /*wait=*/true);
  ASSERT_EQ(shown.size(), 1u);
  EXPECT_EQ(shown[0].frame, 1);
  EXPECT_TRUE(player.at(time_of(sequence, 1), true).empty());  // nothing new to show
  // The worker goes on to frames 2..4 on its own.
  for (int tries = 0; tries < 200 && player.stats().frames_read < 4; ++tries)
    std::this_thread::sleep_for(std::chrono::milliseconds(50));
  EXPECT_EQ(player.stats().frames_read, 4u);
  EXPECT_EQ(player.stats().cached_frames, 4u);
  shown = player.at(time_of(sequence, 3), true);
  ASSERT_EQ(shown.size(), 1u);
  EXPECT_EQ(shown[0].frame, 3);

  // Waiting (a capture): the broken frame is an error naming its file and frame.
  try {
    player.at(time_of(sequence, 6), true);
    ADD_FAILURE() << "a broken frame was shown";
  } catch (const scene::LoadError& error) {
    EXPECT_THAT(std::string(error.what()), AllOf(HasSubstr("plume.0006.vdb"), HasSubstr("frame 6 of the sequence")));
  }
  // Not waiting (the viewer): it is left out, said once, and the volume keeps its frame.
  renderer::VolumeSequencePlayer viewer(scene.volume_sequences, ctx().info().max_image_dimension_3d, options);
  ASSERT_EQ(viewer.at(time_of(sequence, 5), true).size(), 1u);
  std::vector<scene::LoadError> errors;
  for (int tries = 0; tries < 200 && errors.empty(); ++tries) {
    EXPECT_TRUE(viewer.at(time_of(sequence, 6), false).empty());
    errors = viewer.take_errors();
    if (errors.empty()) std::this_thread::sleep_for(std::chrono::milliseconds(50));
  }
  ASSERT_EQ(errors.size(), 1u);
  EXPECT_THAT(std::string(errors[0].what()), HasSubstr("plume.0006.vdb"));
  EXPECT_TRUE(viewer.at(time_of(sequence, 6), false).empty());
  EXPECT_TRUE(viewer.take_errors().empty());
  ASSERT_EQ(viewer.at(time_of(sequence, 7), true).size(), 1u);  // plays on past it

  // Played through and looped, the cache never holds more than it may.
  for (int frame = 7; frame <= 28; ++frame) {  // 25..28 loop to 1..4
    viewer.at(time_of(sequence, frame), true);
    EXPECT_LE(viewer.stats().cached_frames, options.cache_frames);
  }
}

}  // namespace
}  // namespace volume_sequence_test
}  // namespace avsm
