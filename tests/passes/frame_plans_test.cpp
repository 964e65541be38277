// The engine's real frames through the independent plan verifier
// (tests/rendergraph/plan_verifier.h): each frame's plan on its own (hazards between
// aliased transients, which synchronization validation does not see), and the state the
// frames carry from one to the next in the memory they import: the page pool, the page
// tables, the dense maps, the readbacks.
#include <gtest/gtest.h>
#include <rendergraph/rendergraph.h>
#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <any>
#include <iostream>
#include <vector>

#include <glm/gtc/matrix_transform.hpp>

#include "gpu/context.h"
#include "passes/frame/view.h"
#include "passes/shadows/shadow_maps.h"
#include "plan_verifier.h"
#include "renderer/frame_slots.h"
#include "renderer/scene_renderer.h"
#include "scene/scene.h"
#include "support/gpu_test.h"

namespace avsm {
namespace frame_plans_test {  // one per file: test targets are unity builds
namespace {

using FramePlansTest = testing::GpuTest;

constexpr uint32_t kFrameWidth = 96, kFrameHeight = 54;

// The memory behind an import, as rg::vulkan::import carries it: a buffer (or a region
// of one) by its handle and bytes, an image by its handle.
std::optional<rg_test::PhysicalRange> physical_memory(const rg::ResourceDecl& decl) {
  if (const auto* buffer = std::any_cast<const gpu::Buffer*>(&decl.physical))
    return rg_test::PhysicalRange{uint64_t((*buffer)->handle()), (*buffer)->offset(), (*buffer)->offset() + (*buffer)->size()};
  if (const auto* range = std::any_cast<gpu::BufferRange>(&decl.physical))
    return rg_test::PhysicalRange{uint64_t(range->buffer), range->offset, range->offset + decl.buffer.size};
  if (const auto* image = std::any_cast<const gpu::Image*>(&decl.physical))
    return rg_test::PhysicalRange{uint64_t((*image)->handle()), 0, 1};
  return std::nullopt;
}

// Frames as submitted, two in flight: each graph with the plan its slot's executor ran
// it by and the memory of its imports (resolved at once: the regions some imports name
// live only as long as their frame slot's declaration).
struct RecordedFrames {
  std::vector<rg::Graph> graphs;
  std::vector<rg::CompiledPlan> plans;
  std::vector<std::vector<std::optional<rg_test::PhysicalRange>>> memory;
  std::vector<size_t> completed_before;
  size_t completed = 0;                              // frames whose fence the host has waited for
  uint32_t built = 0, evicted = 0, invalidated = 0;  // the paged sun's pages, over the frames finished
  uint32_t point_built = 0, point_evicted = 0;        // the paged point light's, its six faces together
};

void render(renderer::SceneRenderer& renderer, renderer::FrameSlots& slots, const passes::View& view, int frames,
            RecordedFrames& recorded) {
  const renderer::FrameSlots::Finished finished = [&](renderer::FrameSlots::Slot& slot) {
    renderer.finish_frame(slot.index);
    ++recorded.completed;
    const passes::PageStats& pages = *renderer.shadows().frame_stats()[0].pages;
    recorded.built += pages.built;
    recorded.evicted += pages.evicted;
    recorded.invalidated += pages.invalidated;
    const passes::PageStats& point = *renderer.shadows().frame_stats()[2].pages;
    recorded.point_built += point.built;
    recorded.point_evicted += point.evicted;
  };
  for (int i = 0; i < frames; ++i) {
    renderer::FrameSlots::Slot& slot = slots.acquire(finished);
    rg::Graph graph = renderer.build_frame(view, slot.index);
    VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
    begin.flags = VK_COMMAND_BUFFER_USAGE_ONE_TIME_SUBMIT_BIT;
    ASSERT_EQ(vkBeginCommandBuffer(slot.cmd, &begin), VK_SUCCESS);
    slot.executor->record(graph, slot.cmd);
    ASSERT_EQ(vkEndCommandBuffer(slot.cmd), VK_SUCCESS);
    slots.submit(slot);
    recorded.plans.push_back(slot.executor->plan());
    recorded.memory.emplace_back();
    for (const rg::ResourceDecl& decl : graph.resources()) recorded.memory.back().push_back(physical_memory(decl));
    recorded.completed_before.push_back(recorded.completed);
    recorded.graphs.push_back(std::move(graph));
  }
  slots.finish_all(finished);
}

}  // namespace

// The default scene (meshes, smoke, hair) with the sun paged in a pool of 14 pages, the
// spot dense and a point light paged (six faces in one pool of 24), two frames in flight: frames that build the first pages, then a camera
// that goes round the stage (its pages evict others from their slots), then a box that
// moves (pages invalidated and built again in place). Every frame's plan is valid, and every import's initial
// state is what the frames before left in its memory.
TEST_F(FramePlansTest, PagedAndDenseFramesCarryTheirStateFromFrameToFrame) {
  scene::Scene scene = scene::load_scene(AVSM_DEFAULT_SCENE);
  ASSERT_GE(scene.lights.size(), 2u);
  for (scene::Light& light : scene.lights) {
    light.shadow.technique = "avsm";
    light.shadow.nodes = 8;
    light.shadow.resolution = 64;
    light.shadow.kernel = scene::ShadowKernel::none;
  }
  scene::ShadowSettings& sun = scene.lights[0].shadow;
  sun.layout = scene::ShadowLayout::paged;
  sun.fit = scene::ShadowFit::scene;
  sun.virtual_resolution = 2048;
  sun.page_size = 32;
  sun.page_pool_mib = 14.0 * 32 * 32 * 32 / double(1 << 20);  // 14 AVSM-8 pages of 32^2
  scene.lights[1].shadow.layout = scene::ShadowLayout::dense;
  // A paged point light above the stage: its six faces share a pool of 24 pages, so the
  // faces the camera turns to take slots from those it turns away from.
  scene::Light point = scene.lights[1];
  point.name = "point";
  point.type = scene::LightType::point;
  point.position = glm::vec3(0.0f, 2.8f, 0.0f);
  point.range = 12.0f;
  point.shadow.layout = scene::ShadowLayout::paged;
  point.shadow.virtual_resolution = 1024;
  point.shadow.page_size = 32;
  point.shadow.page_pool_mib = 24.0 * 32 * 32 * 32 / double(1 << 20);
  scene.lights.push_back(point);

  renderer::SceneRenderer renderer(ctx(), shaders(), scene, kFrameWidth, kFrameHeight);
  renderer.set_frames_in_flight(2);
  renderer::FrameSlots slots(ctx(), gpu::TimestampMode::Exact, 2);
  RecordedFrames recorded;
  // Four views around the stage, closer each time.
  scene::Camera camera = scene.cameras.front();
  const glm::vec3 offset = camera.position - camera.target;
  for (int view = 0; view < 4; ++view) {
    const glm::vec3 turned = glm::vec3(glm::rotate(glm::mat4(1.0f), glm::radians(90.0f * float(view)), glm::vec3(0, 1, 0)) *
                                       glm::vec4(offset, 0.0f));
    camera.position = camera.target + turned * (1.0f - 0.15f * float(view));
    render(renderer, slots, passes::make_view(camera, kFrameWidth, kFrameHeight), 3, recorded);
  }

  const auto box = std::find_if(scene.meshes.begin(), scene.meshes.end(), [](const scene::Mesh& m) { return m.name == "stage/box"; });
  ASSERT_NE(box, scene.meshes.end());
  scene::Mesh moved = *box;
  for (glm::vec3& p : moved.positions) p.x -= 0.3f;
  moved.bounds = {box->bounds.min - glm::vec3(0.3f, 0, 0), box->bounds.max - glm::vec3(0.3f, 0, 0)};
  renderer.update_mesh(uint32_t(box - scene.meshes.begin()), moved);
  render(renderer, slots, passes::make_view(camera, kFrameWidth, kFrameHeight), 3, recorded);

  std::cout << "[ frame plans ] " << recorded.graphs.size() << " frames; the paged sun built " << recorded.built
            << " pages, evicted " << recorded.evicted << ", invalidated " << recorded.invalidated
            << "; the paged point light's faces built " << recorded.point_built << ", evicted " << recorded.point_evicted
            << "\n";
  EXPECT_GT(recorded.evicted, 0u) << "the camera's move should give some slots to finer pages";
  EXPECT_GT(recorded.invalidated, 0u) << "the box's move should invalidate pages";
  EXPECT_GT(recorded.point_built, 6u) << "the point light's faces build more than their roots";

  std::vector<rg_test::PlannedFrame> frames;
  for (size_t f = 0; f < recorded.graphs.size(); ++f)
    frames.push_back({&recorded.graphs[f], &recorded.plans[f], recorded.memory[f], recorded.completed_before[f]});
  const rg::vulkan::DeviceMemoryModel memory(ctx());
  const std::vector<std::string> problems = rg_test::verify_frames(frames, memory);
  for (const std::string& problem : problems) ADD_FAILURE() << problem;
}

}  // namespace frame_plans_test
}  // namespace avsm
