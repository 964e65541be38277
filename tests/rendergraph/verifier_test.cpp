// The verifier must be able to fail: each test breaks a valid plan in one specific way
// and expects the verifier to name that problem.
#include <gtest/gtest.h>

#include <functional>

#include "mock_memory_model.h"
#include "plan_verifier.h"
#include "test_graphs.h"

namespace rg_test {
namespace verifier_test {  // one per file: test targets are unity builds
namespace {

struct Broken {
  rg::Graph graph;
  rg::CompiledPlan plan;
  MockMemoryModel memory;

  explicit Broken(rg::Graph g, rg::CompileOptions options = {}) : graph(std::move(g)) {
    plan = graph.compile(memory, options);
  }

  uint32_t resource(const std::string& name) const {
    for (uint32_t r = 0; r < plan.resources.size(); ++r)
      if (plan.resources[r].name == name) return r;
    ADD_FAILURE() << "no resource " << name;
    return 0;
  }
  rg::PlannedPass& pass(const std::string& name) {
    for (auto& p : plan.passes)
      if (p.name == name) return p;
    ADD_FAILURE() << "no pass " << name;
    return plan.passes.front();
  }
  // The barrier before pass `pass_name` on resource `resource_name`.
  rg::Barrier& barrier(const std::string& pass_name, const std::string& resource_name) {
    for (auto& b : pass(pass_name).barriers)
      if (!b.is_global() && b.resource == resource(resource_name)) return b;
    ADD_FAILURE() << "no barrier on " << resource_name << " before " << pass_name;
    return pass(pass_name).barriers.front();
  }
  void remove_barrier(const std::string& pass_name, const std::string& resource_name) {
    auto& barriers = pass(pass_name).barriers;
    const uint32_t r = resource(resource_name);
    std::erase_if(barriers, [&](const rg::Barrier& b) { return !b.is_global() && b.resource == r; });
  }

  std::vector<std::string> problems() const { return verify_plan(graph, plan, memory); }
};

// Passes when some problem contains `needle`.
::testing::AssertionResult reports(const std::vector<std::string>& problems, const std::string& needle) {
  for (const auto& p : problems)
    if (p.find(needle) != std::string::npos) return ::testing::AssertionSuccess();
  auto failure = ::testing::AssertionFailure() << "no problem mentions \"" << needle << "\"; got:";
  for (const auto& p : problems) failure << "\n  " << p;
  return failure;
}

TEST(Verifier, AcceptsTheUnbrokenPlans) {
  for (auto make : {diamond_graph, culled_branch_graph, buffer_raw_graph, history_graph})
    EXPECT_TRUE(Broken(make()).problems().empty());
  EXPECT_TRUE(Broken(multi_light_graph(3)).problems().empty());
}

TEST(Verifier, RemovedReadAfterWriteBarrier) {
  Broken b(buffer_raw_graph());
  b.remove_barrier("cull", "instances");
  EXPECT_TRUE(reports(b.problems(), "RAW hazard on 'instances': pass 'cull' (StorageRead) is not ordered after pass 'upload'"));
}

TEST(Verifier, RemovedWriteAfterReadBarrier) {
  Broken b(buffer_raw_graph());
  b.remove_barrier("copy_stats", "stats_readback");  // the host read of the previous frame
  EXPECT_TRUE(reports(b.problems(), "WAR hazard on 'stats_readback'"));
}

TEST(Verifier, BarrierWithTooFewDstAccesses) {
  Broken b(buffer_raw_graph());
  b.barrier("draw", "draw_args").dst_access = VK_ACCESS_2_SHADER_STORAGE_READ_BIT;  // not the indirect read
  EXPECT_TRUE(reports(b.problems(), "RAW hazard on 'draw_args'"));
}

TEST(Verifier, TransitionWithTheWrongSrcStage) {
  Broken b(diamond_graph());
  b.barrier("ssao", "depth").src_stages = VK_PIPELINE_STAGE_2_COLOR_ATTACHMENT_OUTPUT_BIT;
  EXPECT_TRUE(reports(b.problems(), "layout transition of 'depth' is not ordered after pass 'gbuffer'"));
}

TEST(Verifier, WrongLayoutForTheUsage) {
  Broken b(diamond_graph());
  b.barrier("ssao", "normal").new_layout = VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL;
  EXPECT_TRUE(reports(b.problems(), "'normal' is in TRANSFER_DST_OPTIMAL when pass 'ssao' uses it as Sampled"));
}

TEST(Verifier, TransitionFromTheWrongOldLayout) {
  Broken b(diamond_graph());
  b.barrier("combine", "ao").old_layout = VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL;
  EXPECT_TRUE(reports(b.problems(), "barrier on 'ao' from SHADER_READ_ONLY_OPTIMAL but it is in GENERAL"));
}

TEST(Verifier, TransitionThatDiscardsLiveContents) {
  Broken b(diamond_graph());
  b.barrier("combine", "ao").old_layout = VK_IMAGE_LAYOUT_UNDEFINED;
  EXPECT_TRUE(reports(b.problems(), "(discards contents)"));
}

TEST(Verifier, MissingFinalTransition) {
  Broken b(multi_light_graph(2));
  b.plan.final_barriers.clear();
  EXPECT_TRUE(reports(b.problems(), "'frame' ends in COLOR_ATTACHMENT_OPTIMAL instead of its final PRESENT_SRC"));
}

TEST(Verifier, OverlappingPlacementsWhileAlive) {
  Broken b(multi_light_graph(2));
  b.plan.resources[b.resource("sort_scratch_0")].offset = 0;  // on top of nodes_0, alive at the same time
  EXPECT_TRUE(reports(b.problems(), "'nodes_0' and 'sort_scratch_0' overlap in memory while both alive"));
}

TEST(Verifier, OverlapWithAliasingOff) {
  Broken b(multi_light_graph(2), {.aliasing = false});
  b.plan.resources[b.resource("nodes_1")].offset = b.plan.resources[b.resource("nodes_0")].offset;
  EXPECT_TRUE(reports(b.problems(), "share memory with aliasing off"));
}

TEST(Verifier, ImageAndBufferSharingAGranularityPage) {
  Broken b(multi_light_graph(2));
  // sort_scratch_0 (a buffer) ends 256 bytes into a 1 KiB page and head_0 (an image)
  // starts 256 bytes after it: no byte is shared, but a bufferImageGranularity page is,
  // while both are alive.
  auto& head = b.plan.resources[b.resource("head_0")];
  auto& scratch = b.plan.resources[b.resource("sort_scratch_0")];
  scratch.offset += 256;
  head.offset = scratch.offset + scratch.size + 256;
  EXPECT_TRUE(reports(b.problems(), "'head_0' and 'sort_scratch_0' overlap in memory while both alive"));
}

TEST(Verifier, MisalignedPlacement) {
  Broken b(diamond_graph());
  b.plan.resources[b.resource("ao")].offset += 256;
  EXPECT_TRUE(reports(b.problems(), "'ao': offset"));
}

TEST(Verifier, MissingAliasingBarrier) {
  Broken b(multi_light_graph(2));
  rg::Barrier& first_use = b.barrier("capture_1", "nodes_1");
  ASSERT_FALSE(first_use.aliased.empty());
  b.remove_barrier("capture_1", "nodes_1");
  EXPECT_TRUE(reports(b.problems(), "aliasing hazard on 'nodes_1'"));
}

TEST(Verifier, AliasingTransitionThatDoesNotWaitForThePreviousOccupant) {
  Broken b(multi_light_graph(2));
  rg::Barrier& first_use = b.barrier("capture_1", "head_1");
  ASSERT_EQ(first_use.aliased, std::vector<uint32_t>{b.resource("head_0")});
  first_use.src_stages = VK_PIPELINE_STAGE_2_NONE;
  first_use.src_access = VK_ACCESS_2_NONE;
  EXPECT_TRUE(reports(b.problems(), "layout transition of 'head_1' is not ordered after pass 'resolve_0'"));
}

TEST(Verifier, CulledAnchorPass) {
  Broken b(culled_branch_graph());
  auto& passes = b.plan.passes;
  auto it = std::find_if(passes.begin(), passes.end(), [](const rg::PlannedPass& p) { return p.name == "depth_readback"; });
  b.plan.culled_passes.push_back(*it);
  passes.erase(it);
  EXPECT_TRUE(reports(b.problems(), "anchored pass 'depth_readback' was culled"));
}

TEST(Verifier, KeptPassThatNothingNeeds) {
  Broken b(culled_branch_graph(), {.culling = false});
  b.plan.options.culling = true;  // claims culling but kept the debug branch
  EXPECT_TRUE(reports(b.problems(), "pass 'debug_overlay' is kept but unused"));
}

TEST(Verifier, ReaderScheduledBeforeItsProducer) {
  Broken b(diamond_graph());
  std::swap(b.plan.passes[0], b.plan.passes[1]);  // ssao before gbuffer
  EXPECT_TRUE(reports(b.problems(), "pass 'ssao' reads 'depth' version 1 but its producer 'gbuffer' does not run before it"));
}

// --- persistent state across frames (verify_frames) --------------------------------------

// A persistent map of 1024 bytes: a frame builds the bytes [offset, offset + size) in
// compute (importing them as `initial`, leaving them in `final_state`) and a later pass
// reads them in the fragment shader.
rg::Graph persistent_map_frame(rg::ImportState initial, rg::ImportState final_state, uint64_t offset = 0,
                               uint64_t size = 1024) {
  rg::Graph graph;
  auto map = graph.import_buffer("map " + std::to_string(offset), {size}, initial, final_state);
  graph.add_pass("build", rg::QueueType::Compute,
                 [&](rg::PassBuilder& b) { map = b.write(map, rg::Usage::StorageWrite); }, no_execute);
  graph.add_pass("shade", rg::QueueType::Graphics, [&](rg::PassBuilder& b) {
    b.read(map, rg::Usage::StorageRead);
    b.side_effect();
  }, no_execute);
  return graph;
}

// The memory behind "map <offset>" imports: one buffer, at that offset; the rest by name.
std::optional<PhysicalRange> map_memory(const rg::ResourceDecl& decl) {
  if (decl.name.rfind("map ", 0) == 0) {
    const uint64_t offset = std::stoull(decl.name.substr(4));
    return PhysicalRange{1, offset, offset + decl.buffer.size};
  }
  return PhysicalRange{std::hash<std::string>{}(decl.name), 0, 1};
}

struct Frames {
  MockMemoryModel memory;
  std::vector<rg::Graph> graphs;
  std::vector<rg::CompiledPlan> plans;

  std::vector<size_t> completed_before;

  // A frame submitted once frames [0, completed) have completed.
  void add(rg::Graph graph, size_t completed = 0) {
    plans.push_back(graph.compile(memory));
    graphs.push_back(std::move(graph));
    completed_before.push_back(completed);
  }
  std::vector<std::string> problems() const {
    std::vector<PlannedFrame> frames;
    for (size_t f = 0; f < graphs.size(); ++f) {
      frames.push_back({&graphs[f], &plans[f], {}, completed_before[f]});
      for (const rg::ResourceDecl& decl : graphs[f].resources()) frames.back().memory.push_back(map_memory(decl));
    }
    return verify_frames(frames, memory);
  }
};

const rg::ImportState kReadInShaders = rg::ImportState::of(rg::Usage::StorageRead);

TEST(VerifierFrames, AcceptsFramesThatCarryTheirState) {
  Frames frames;
  for (int f = 0; f < 3; ++f) frames.add(history_graph());
  EXPECT_TRUE(frames.problems().empty()) << testing::PrintToString(frames.problems());
  Frames maps;
  for (int f = 0; f < 3; ++f) maps.add(persistent_map_frame(kReadInShaders, kReadInShaders));
  EXPECT_TRUE(maps.problems().empty()) << testing::PrintToString(maps.problems());
}

// The frame before left the map to whoever comes next without a final barrier: the
// fragment shader's read is still open, and the next frame's build does not wait for it.
TEST(VerifierFrames, AnOpenReadTheNextFrameDoesNotWaitFor) {
  Frames frames;
  frames.add(persistent_map_frame(rg::ImportState::none(), rg::ImportState::none()));
  frames.add(persistent_map_frame(rg::ImportState::none(), rg::ImportState::none()));
  EXPECT_TRUE(reports(frames.problems(), "frame 1: 'map 0' starts in a state frame 0's 'map 0' did not leave: "
                                         "pass 'shade' (StorageRead) is still open"));
}

// A frame-slot buffer (a readback, parameters the host writes) is used again only after
// the host waited for the frame that used it last: nothing of that frame is pending.
TEST(VerifierFrames, NothingIsPendingFromAFrameTheHostWaitedFor) {
  Frames frames;
  frames.add(persistent_map_frame(rg::ImportState::none(), rg::ImportState::none()));
  frames.add(persistent_map_frame(rg::ImportState::none(), rg::ImportState::none()), 1);
  EXPECT_TRUE(frames.problems().empty()) << testing::PrintToString(frames.problems());
}

// The frame before made its writes visible to compute only; the next claims them visible
// to the fragment shader as well.
TEST(VerifierFrames, AClaimOfVisibilityTheFinalStateDidNotMake) {
  Frames frames;
  const rg::ImportState compute_read = rg::ImportState::of(rg::Usage::StorageRead, rg::QueueType::Compute);
  frames.add(persistent_map_frame(kReadInShaders, compute_read));
  frames.add(persistent_map_frame(kReadInShaders, kReadInShaders));
  EXPECT_TRUE(reports(frames.problems(), "frame 1: 'map 0' starts in a state frame 0's 'map 0' did not leave: it claims"));
}

// Persistent state is memory, not names: a frame that builds a page into the slot another
// page used must wait for what the frames before did there.
TEST(VerifierFrames, StateFollowsTheMemoryAcrossImportsOfOtherNames) {
  Frames frames;
  frames.add(persistent_map_frame(kReadInShaders, rg::ImportState::none(), 0, 512));
  frames.add(persistent_map_frame(rg::ImportState::none(), kReadInShaders, 256, 512));
  EXPECT_TRUE(reports(frames.problems(), "frame 1: 'map 256' starts in a state frame 0's 'map 0' did not leave"));
}

TEST(VerifierFrames, AnImageInAnotherLayoutThanTheFrameBeforeLeftIt) {
  Frames frames;
  frames.add(history_graph());
  rg::Graph second;
  auto history = second.import_texture("taa_history", texture_desc(256, 256, VK_FORMAT_R16G16B16A16_SFLOAT),
                                       rg::ImportState::of(rg::Usage::StorageRead, rg::QueueType::Compute),
                                       rg::ImportState::of(rg::Usage::StorageRead, rg::QueueType::Compute));
  second.add_pass("taa", rg::QueueType::Compute, [&](rg::PassBuilder& b) {
    b.read(history, rg::Usage::StorageRead);
    b.side_effect();
  }, no_execute);
  frames.add(std::move(second));
  EXPECT_TRUE(reports(frames.problems(), "'taa_history' starts in a state frame 0's 'taa_history' did not leave: layout "
                                         "GENERAL instead of SHADER_READ_ONLY_OPTIMAL"));
}

// Two imports of one buffer's bytes are one memory to the device: a write to one and a
// read of the other need a barrier between them, though the planner sees two resources.
TEST(VerifierFrames, AWriteToOneImportOfSharedMemoryAndAnUnorderedReadOfAnother) {
  Frames frames;
  rg::Graph graph;
  auto whole = graph.import_buffer("map 0", {1024}, kReadInShaders, kReadInShaders);
  auto part = graph.import_buffer("map 512", {256}, kReadInShaders, kReadInShaders);
  graph.add_pass("build part", rg::QueueType::Compute,
                 [&](rg::PassBuilder& b) { part = b.write(part, rg::Usage::StorageWrite); }, no_execute);
  graph.add_pass("shade", rg::QueueType::Graphics, [&](rg::PassBuilder& b) {
    b.read(whole, rg::Usage::StorageRead);
    b.side_effect();
  }, no_execute);
  frames.add(std::move(graph));
  EXPECT_TRUE(reports(frames.problems(), "frame 0: hazard on the memory 'map 0' and 'map 512' share: pass 'shade'"));
}

TEST(VerifierFrames, APassThatWritesOneImportOfSharedMemoryAndReadsAnother) {
  Frames frames;
  rg::Graph graph;
  auto whole = graph.import_buffer("map 0", {1024}, kReadInShaders, kReadInShaders);
  auto part = graph.import_buffer("map 512", {256}, kReadInShaders, kReadInShaders);
  graph.add_pass("build part from whole", rg::QueueType::Compute, [&](rg::PassBuilder& b) {
    b.read(whole, rg::Usage::StorageRead);
    part = b.write(part, rg::Usage::StorageWrite);
  }, no_execute);
  frames.add(std::move(graph));
  EXPECT_TRUE(reports(frames.problems(), "pass 'build part from whole' uses"));
}

}  // namespace
}  // namespace verifier_test
}  // namespace rg_test
