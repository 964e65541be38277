// Golden-plan tests: small graphs whose whole plan (order, barriers, placements, culling)
// is compared with a reviewed dump in golden/. Every plan also passes the verifier.
#include <gtest/gtest.h>

#include "golden.h"
#include "mock_memory_model.h"
#include "plan_verifier.h"
#include "test_graphs.h"

namespace rg_test {
namespace golden_test {  // one per file: test targets are unity builds
namespace {

::testing::AssertionResult valid(const rg::Graph& graph, const rg::CompiledPlan& plan, const rg::MemoryModel& memory) {
  const auto problems = verify_plan(graph, plan, memory);
  if (problems.empty()) return ::testing::AssertionSuccess();
  auto failure = ::testing::AssertionFailure() << "verifier found " << problems.size() << " problem(s):";
  for (const auto& p : problems) failure << "\n  " << p;
  return failure;
}

void expect_golden(const char* name, const rg::Graph& graph, const rg::MemoryModel& memory) {
  const rg::CompiledPlan plan = graph.compile(memory);
  EXPECT_TRUE(valid(graph, plan, memory));
  EXPECT_TRUE(matches_golden(name, plan.to_text()));
}

TEST(GoldenPlan, Diamond) { expect_golden("diamond", diamond_graph(), MockMemoryModel()); }

TEST(GoldenPlan, CulledBranch) { expect_golden("culled_branch", culled_branch_graph(), MockMemoryModel()); }

TEST(GoldenPlan, MultiLightChainAliasesPerLightTransients) {
  expect_golden("multi_light", multi_light_graph(3), MockMemoryModel());
}

TEST(GoldenPlan, BufferReadAfterWrite) { expect_golden("buffer_raw", buffer_raw_graph(), MockMemoryModel()); }

TEST(GoldenPlan, MipChainInBufferRanges) { expect_golden("mip_chain", mip_chain_graph(), MockMemoryModel()); }

TEST(GoldenPlan, ImportedAndHistoryResources) { expect_golden("history", history_graph(), MockMemoryModel()); }

// Render targets in their own memory class and a coarse bufferImageGranularity (4 KiB,
// above the 1 KiB alignment of small images): separate heaps, page-aligned images.
TEST(GoldenPlan, DiamondTwoMemoryClassesCoarseGranularity) {
  expect_golden("diamond_two_classes", diamond_graph(), MockMemoryModel({.split_render_targets = true, .granularity = 4096}));
}

TEST(GoldenPlan, MultiLightSerialNoAliasing) {
  const rg::Graph graph = multi_light_graph(2);
  const MockMemoryModel memory;
  const rg::CompiledPlan plan = graph.compile(memory, {.aliasing = false, .culling = true, .serial_full_barriers = true});
  EXPECT_TRUE(valid(graph, plan, memory));
  EXPECT_TRUE(matches_golden("multi_light_serial_no_aliasing", plan.to_text()));
}

}  // namespace
}  // namespace golden_test
}  // namespace rg_test
