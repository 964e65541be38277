// Buffer ranges: passes touching disjoint ranges of one buffer need no barrier between
// them, overlapping ones do (for exactly the overlapping bytes), a whole-buffer access
// waits for every range, and the verifier checks plans range by range.
#include <gtest/gtest.h>

#include "mock_memory_model.h"
#include "plan_verifier.h"
#include "test_graphs.h"

namespace rg_test {
namespace buffer_range_test {  // one per file: test targets are unity builds
namespace {

using rg::BufferRange;
using rg::PassBuilder;
using rg::QueueType;
using rg::Usage;

const rg::PlannedPass& planned(const rg::CompiledPlan& plan, const std::string& name) {
  for (const rg::PlannedPass& pass : plan.passes)
    if (pass.name == name) return pass;
  ADD_FAILURE() << "no pass " << name;
  return plan.passes.front();
}

std::string problems_text(const std::vector<std::string>& problems) {
  std::string text;
  for (const std::string& problem : problems) text += "\n  " + problem;
  return text;
}

::testing::AssertionResult reports(const std::vector<std::string>& problems, const std::string& needle) {
  for (const std::string& problem : problems)
    if (problem.find(needle) != std::string::npos) return ::testing::AssertionSuccess();
  return ::testing::AssertionFailure() << "no problem mentions \"" << needle << "\"; got:" << problems_text(problems);
}

// Two compute passes writing `first` and `second` of a 256-byte buffer, then a whole read.
rg::Graph two_writes_then_read(BufferRange first, BufferRange second, Usage second_usage = Usage::StorageWrite) {
  rg::Graph graph;
  auto buffer = graph.import_buffer("buffer", {256}, rg::ImportState::none(), rg::ImportState::none());
  graph.add_pass("first", QueueType::Compute, [&](PassBuilder& b) {
    buffer = b.write(buffer, Usage::StorageWrite, first);
  }, no_execute);
  graph.add_pass("second", QueueType::Compute, [&](PassBuilder& b) {
    if (second_usage == Usage::StorageWrite)
      buffer = b.write(buffer, second_usage, second);
    else
      b.read(buffer, second_usage, second);
    b.side_effect();  // a reader nobody depends on
  }, no_execute);
  graph.add_pass("read", QueueType::Compute, [&](PassBuilder& b) {
    b.read(buffer, Usage::StorageRead);
    b.side_effect();
  }, no_execute);
  return graph;
}

TEST(BufferRanges, DisjointRangesNeedNoBarrier) {
  const MockMemoryModel memory;
  const rg::Graph graph = two_writes_then_read({0, 128}, {128, 128});
  const rg::CompiledPlan plan = graph.compile(memory);
  EXPECT_TRUE(planned(plan, "second").barriers.empty());
  // Both halves were written by compute shaders: one barrier over the whole buffer.
  ASSERT_EQ(planned(plan, "read").barriers.size(), 1u);
  EXPECT_TRUE(planned(plan, "read").barriers[0].range.whole());
  EXPECT_TRUE(verify_plan(graph, plan, memory).empty()) << problems_text(verify_plan(graph, plan, memory));
}

TEST(BufferRanges, OverlappingRangesWaitForTheOverlapOnly) {
  const MockMemoryModel memory;
  const rg::Graph graph = two_writes_then_read({0, 128}, {64, 128}, Usage::StorageRead);
  const rg::CompiledPlan plan = graph.compile(memory);
  const std::vector<rg::Barrier>& barriers = planned(plan, "second").barriers;
  ASSERT_EQ(barriers.size(), 1u);
  EXPECT_EQ(barriers[0].range, (BufferRange{64, 64}));  // bytes [64, 128): written by "first"
  EXPECT_EQ(barriers[0].src_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_TRUE(verify_plan(graph, plan, memory).empty()) << problems_text(verify_plan(graph, plan, memory));
}

TEST(BufferRanges, WriteAfterWriteOfOverlappingRanges) {
  const MockMemoryModel memory;
  const rg::Graph graph = two_writes_then_read({0, 128}, {64, 128});
  const rg::CompiledPlan plan = graph.compile(memory);
  const std::vector<rg::Barrier>& barriers = planned(plan, "second").barriers;
  ASSERT_EQ(barriers.size(), 1u);
  EXPECT_EQ(barriers[0].range, (BufferRange{64, 64}));
  EXPECT_EQ(barriers[0].dst_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_TRUE(verify_plan(graph, plan, memory).empty()) << problems_text(verify_plan(graph, plan, memory));
}

TEST(BufferRanges, MipChainBarriersNameTheLevels) {
  const MockMemoryModel memory;
  const rg::CompiledPlan plan = mip_chain_graph().compile(memory);
  // Level 0 becomes mip 1's source (RAW); level 1's bytes were last written by the resolve (WAW).
  const std::vector<rg::Barrier>& mip1 = planned(plan, "mip 1").barriers;
  ASSERT_EQ(mip1.size(), 2u);
  EXPECT_EQ(mip1[0].range, (BufferRange{0, 1024}));
  EXPECT_EQ(mip1[0].dst_access, VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  EXPECT_EQ(mip1[1].range, (BufferRange{1024, 256}));
  EXPECT_EQ(mip1[1].dst_access, VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  // Shading reads every level: one barrier, as all bytes were last written by compute.
  ASSERT_EQ(planned(plan, "shade").barriers.size(), 1u);
  EXPECT_TRUE(planned(plan, "shade").barriers[0].range.whole());
}

TEST(BufferRanges, WritingARangeKeepsTheProducerOfTheRest) {
  // Nobody reads what "resolve" wrote into level 0 except through the later whole read:
  // the partial writes of the mips must keep it.
  rg::Graph graph;
  auto map = graph.import_buffer("map", {512}, rg::ImportState::none(), rg::ImportState::none());
  rg::BufferHandle scratch;
  graph.add_pass("fill", QueueType::Compute, [&](PassBuilder& b) {
    scratch = b.write(b.create_buffer("scratch", {512}), Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("patch", QueueType::Compute, [&](PassBuilder& b) {
    scratch = b.write(scratch, Usage::StorageWrite, {256, 256});
  }, no_execute);
  graph.add_pass("consume", QueueType::Compute, [&](PassBuilder& b) {
    b.read(scratch, Usage::StorageRead);
    map = b.write(map, Usage::StorageWrite);
  }, no_execute);
  const MockMemoryModel memory;
  const rg::CompiledPlan plan = graph.compile(memory);
  EXPECT_EQ(plan.passes.size(), 3u);
  EXPECT_TRUE(plan.culled_passes.empty());
  EXPECT_TRUE(verify_plan(graph, plan, memory).empty()) << problems_text(verify_plan(graph, plan, memory));
}

TEST(BufferRanges, ShapeHashSeesTheRange) {
  auto hash = [](BufferRange range) { return two_writes_then_read({0, 128}, range).shape_hash(); };
  EXPECT_NE(hash({128, 128}), hash({128, 64}));
  EXPECT_EQ(hash({128, 128}), hash({128, 128}));
}

TEST(BufferRanges, TextDumpPrintsRangesOfPartialAccessesOnly) {
  const std::string text = two_writes_then_read({0, 128}, {128, 128}).compile(MockMemoryModel()).to_text();
  EXPECT_NE(text.find("write 'buffer' [128, 256) ->@2 StorageWrite"), std::string::npos) << text;
  EXPECT_NE(text.find("read 'buffer' @2 StorageRead"), std::string::npos) << text;
}

// ---- declaration errors ----

std::string setup_error(const std::function<void(PassBuilder&, rg::BufferHandle)>& setup) {
  rg::Graph graph;
  auto buffer = graph.import_buffer("buffer", {256}, rg::ImportState::of(Usage::StorageRead), rg::ImportState::none());
  try {
    graph.add_pass("p", QueueType::Compute, [&](PassBuilder& b) { setup(b, buffer); }, no_execute);
  } catch (const rg::GraphError& e) {
    return e.what();
  }
  return "";
}

TEST(BufferRanges, OverlappingRangesInOnePassAreRefused) {
  EXPECT_EQ(setup_error([](PassBuilder& b, rg::BufferHandle buffer) {
              b.read(buffer, Usage::StorageRead, {0, 128});
              b.write(buffer, Usage::StorageWrite, {64, 128});
            }),
            "pass 'p': uses overlapping ranges of 'buffer'; one pass sees each byte in one state");
}

TEST(BufferRanges, RangesOutsideTheBufferAreRefused) {
  EXPECT_EQ(setup_error([](PassBuilder& b, rg::BufferHandle buffer) { b.read(buffer, Usage::StorageRead, {200, 64}); }),
            "pass 'p': range at 200 of 64 bytes is empty or leaves buffer 'buffer' (256 bytes)");
  EXPECT_EQ(setup_error([](PassBuilder& b, rg::BufferHandle buffer) { b.read(buffer, Usage::StorageRead, {16, 0}); }),
            "pass 'p': range at 16 of 0 bytes is empty or leaves buffer 'buffer' (256 bytes)");
}

TEST(BufferRanges, SameRangeMergesAndTheWholeRangeIsCanonical) {
  rg::Graph graph;
  auto buffer = graph.import_buffer("buffer", {256}, rg::ImportState::of(Usage::StorageRead), rg::ImportState::none());
  graph.add_pass("p", QueueType::Compute, [&](PassBuilder& b) {
    b.read(buffer, Usage::StorageRead, {0, 64});
    b.read(buffer, Usage::UniformRead, {0, 64});
    buffer = b.read_write(buffer, Usage::StorageReadWrite, {64, rg::kWholeSize});
  }, no_execute);
  graph.add_pass("q", QueueType::Compute, [&](PassBuilder& b) {
    b.read(buffer, Usage::StorageRead, {0, 256});
    b.read(buffer, Usage::UniformRead);
  }, no_execute);
  const auto& p = graph.passes()[0].accesses;
  ASSERT_EQ(p.size(), 2u);
  EXPECT_EQ(p[0].usages, (rg::UsageSet{Usage::StorageRead, Usage::UniformRead}));
  EXPECT_EQ(p[1].range, (BufferRange{64, 192}));  // "to the end" made explicit
  const auto& q = graph.passes()[1].accesses;
  ASSERT_EQ(q.size(), 1u);  // {0, 256} is the whole buffer: the same access as no range
  EXPECT_TRUE(q[0].range.whole());
}

// ---- the verifier checks ranges ----

struct BrokenMipChain {
  rg::Graph graph = mip_chain_graph();
  MockMemoryModel memory;
  rg::CompiledPlan plan = graph.compile(memory);

  std::vector<rg::Barrier>& barriers(const std::string& pass) {
    for (rg::PlannedPass& p : plan.passes)
      if (p.name == pass) return p.barriers;
    ADD_FAILURE() << "no pass " << pass;
    return plan.passes.front().barriers;
  }
  std::vector<std::string> problems() const { return verify_plan(graph, plan, memory); }
};

TEST(BufferRanges, VerifierAcceptsTheMipChain) {
  BrokenMipChain chain;
  EXPECT_TRUE(chain.problems().empty()) << problems_text(chain.problems());
}

TEST(BufferRanges, VerifierCatchesAMissingLevelBarrier) {
  BrokenMipChain chain;
  std::vector<rg::Barrier>& barriers = chain.barriers("mip 2");
  std::erase_if(barriers, [](const rg::Barrier& b) { return b.range == BufferRange{1024, 256}; });
  EXPECT_TRUE(reports(chain.problems(), "RAW hazard on 'map' bytes [1024, 1280): pass 'mip 2' (StorageRead) is not "
                                        "ordered after pass 'mip 1' (StorageWrite)"));
}

TEST(BufferRanges, VerifierCatchesABarrierOverTheWrongBytes) {
  BrokenMipChain chain;
  // mip 2 reads level 1, but its barrier was moved onto level 2's bytes.
  for (rg::Barrier& b : chain.barriers("mip 2"))
    if (b.range == BufferRange{1024, 256}) b.range = {1280, 64};
  EXPECT_TRUE(reports(chain.problems(), "RAW hazard on 'map' bytes [1024, 1280)"));
}

TEST(BufferRanges, VerifierCatchesAWholeReadMissingARange) {
  BrokenMipChain chain;
  // The shading barrier covers levels 0 and 1 only: level 2's write is not waited for.
  std::vector<rg::Barrier>& barriers = chain.barriers("shade");
  ASSERT_EQ(barriers.size(), 1u);
  barriers[0].range = {0, 1280};
  EXPECT_TRUE(reports(chain.problems(), "RAW hazard on 'map' bytes [1280, 1344): pass 'shade' (StorageRead) is not "
                                        "ordered after pass 'mip 2' (StorageWrite)"));
}

}  // namespace
}  // namespace buffer_range_test
}  // namespace rg_test
