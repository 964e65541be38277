// Properties of plans that the goldens do not pin down: determinism, shape hashing, debug
// switches, what the executor reads (usage flags, aspects, execute callbacks), dumps.
#include <gtest/gtest.h>

#include <nlohmann/json.hpp>

#include "mock_memory_model.h"
#include "plan_verifier.h"
#include "test_graphs.h"

namespace rg_test {
namespace plan_test {  // one per file: test targets are unity builds
namespace {

using rg::PassBuilder;
using rg::QueueType;
using rg::Usage;

uint32_t find_resource(const rg::CompiledPlan& plan, const std::string& name) {
  for (uint32_t r = 0; r < plan.resources.size(); ++r)
    if (plan.resources[r].name == name) return r;
  ADD_FAILURE() << "no resource " << name;
  return 0;
}

void expect_valid(const rg::Graph& graph, const rg::CompiledPlan& plan, const rg::MemoryModel& memory) {
  for (const auto& problem : verify_plan(graph, plan, memory)) ADD_FAILURE() << problem;
}

TEST(Plan, CompilingIsDeterministic) {
  const MockMemoryModel memory;
  const rg::Graph a = multi_light_graph(4), b = multi_light_graph(4);
  EXPECT_EQ(a.compile(memory).to_text(), a.compile(memory).to_text());
  EXPECT_EQ(a.compile(memory).to_text(), b.compile(memory).to_text());
  EXPECT_EQ(a.compile(memory).to_json(), b.compile(memory).to_json());
}

TEST(Plan, ShapeHashIgnoresCallbacksButSeesEverythingElse) {
  auto build = [](uint32_t width, Usage read_usage, std::function<void(rg::PassContext&)> execute) {
    rg::Graph graph;
    auto out = graph.import_buffer("out", {64}, rg::ImportState::none(), rg::ImportState::of(Usage::HostRead));
    rg::TextureHandle image;
    graph.add_pass("make", QueueType::Compute, [&](PassBuilder& b) {
      image = b.write(b.create_texture("image", texture_desc(width, 64, VK_FORMAT_R8G8B8A8_UNORM)), Usage::StorageWrite);
    }, execute);
    graph.add_pass("use", QueueType::Compute, [&](PassBuilder& b) {
      b.read(image, read_usage);
      b.write(out, Usage::StorageWrite);
    }, execute);
    return graph;
  };
  int calls = 0;
  const uint64_t base = build(64, Usage::Sampled, no_execute).shape_hash();
  EXPECT_EQ(base, build(64, Usage::Sampled, [&](rg::PassContext&) { ++calls; }).shape_hash());
  EXPECT_NE(base, build(128, Usage::Sampled, no_execute).shape_hash());      // a desc
  EXPECT_NE(base, build(64, Usage::StorageRead, no_execute).shape_hash());   // an access
  const rg::Graph graph = build(64, Usage::Sampled, no_execute);
  EXPECT_NE(base, graph.shape_hash({.aliasing = false}));                    // options
  EXPECT_EQ(graph.compile(MockMemoryModel()).shape_hash, base);
  EXPECT_EQ(calls, 0);  // the core never runs execute callbacks
}

TEST(Plan, ExecutorFindsCallbacksQueuesAndFlags) {
  const rg::Graph graph = buffer_raw_graph();
  const rg::CompiledPlan plan = graph.compile(MockMemoryModel());
  for (const rg::PlannedPass& pass : plan.passes) {
    const rg::PassDecl& decl = graph.passes()[pass.pass_index];
    EXPECT_EQ(decl.name, pass.name);
    EXPECT_EQ(decl.queue, pass.queue);  // recorded for timing / async compute, barriers assume one queue
    EXPECT_TRUE(static_cast<bool>(decl.execute));
  }
  EXPECT_EQ(plan.passes[0].queue, QueueType::Transfer);
  const auto& args = plan.resources[find_resource(plan, "draw_args")];
  EXPECT_EQ(args.buffer_usage, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT |
                                   VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT);
  const auto& color = plan.resources[find_resource(plan, "color")];
  EXPECT_EQ(color.image_usage, VkImageUsageFlags{VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT});
  EXPECT_EQ(color.aspect, VkImageAspectFlags{VK_IMAGE_ASPECT_COLOR_BIT});

  const rg::CompiledPlan diamond = diamond_graph().compile(MockMemoryModel());
  const auto& depth = diamond.resources[find_resource(diamond, "depth")];
  EXPECT_EQ(depth.aspect, VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT});
  EXPECT_EQ(depth.image_usage, VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_DEPTH_STENCIL_ATTACHMENT_BIT);
  // The access carries the layout a descriptor or attachment must use.
  const rg::PlannedAccess& sampled = diamond.passes[1].accesses[0];
  EXPECT_EQ(sampled.layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  EXPECT_EQ(sampled.stages, VkPipelineStageFlags2{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT});
}

TEST(Plan, CullingOffKeepsEveryPass) {
  const rg::Graph graph = culled_branch_graph();
  const MockMemoryModel memory;
  const rg::CompiledPlan plan = graph.compile(memory, {.culling = false});
  EXPECT_TRUE(plan.culled_passes.empty());
  EXPECT_EQ(plan.passes.size(), graph.passes().size());
  EXPECT_TRUE(plan.resources[find_resource(plan, "overlay")].used);
  expect_valid(graph, plan, memory);
}

TEST(Plan, AliasingOffGivesEveryTransientItsOwnMemory) {
  const rg::Graph graph = multi_light_graph(3);
  const MockMemoryModel memory;
  const rg::CompiledPlan plan = graph.compile(memory, {.aliasing = false});
  EXPECT_EQ(plan.stats.transient_bytes_aliased, plan.stats.transient_bytes_unaliased);  // sizes are aligned here
  for (const auto& pass : plan.passes)
    for (const auto& barrier : pass.barriers) EXPECT_TRUE(barrier.aliased.empty());
  expect_valid(graph, plan, memory);

  const rg::CompiledPlan aliased = graph.compile(memory);
  EXPECT_EQ(aliased.stats.transient_bytes_aliased * 3, aliased.stats.transient_bytes_unaliased);
}

TEST(Plan, SerialModeAddsAFullBarrierBetweenPasses) {
  const rg::Graph graph = history_graph();
  const MockMemoryModel memory;
  const rg::CompiledPlan plan = graph.compile(memory, {.serial_full_barriers = true});
  for (size_t i = 0; i < plan.passes.size(); ++i) {
    const bool has_global = std::any_of(plan.passes[i].barriers.begin(), plan.passes[i].barriers.end(),
                                        [](const rg::Barrier& b) { return b.is_global(); });
    EXPECT_EQ(has_global, i > 0);
  }
  expect_valid(graph, plan, memory);
}

// bufferImageGranularity above an image's alignment: images start on, and fill, whole
// pages, so buffers packed around them never share a page with them.
TEST(Plan, ImagesArePageAlignedWhenGranularityExceedsAlignment) {
  rg::Graph graph;
  auto out = graph.import_buffer("out", {64}, rg::ImportState::none(), rg::ImportState::none());
  graph.add_pass("p", QueueType::Compute, [&](PassBuilder& b) {
    b.write(b.create_buffer("a", {300}), Usage::StorageWrite);
    b.write(b.create_texture("small", texture_desc(16, 16, VK_FORMAT_R8G8B8A8_UNORM)), Usage::StorageWrite);  // 1 KiB
    b.write(b.create_buffer("b", {300}), Usage::StorageWrite);
    b.write(out, Usage::StorageWrite);
  }, no_execute);
  const MockMemoryModel memory({.granularity = 4096});
  const rg::CompiledPlan plan = graph.compile(memory);
  const auto& small = plan.resources[find_resource(plan, "small")];
  EXPECT_EQ(small.alignment, 1024u);
  EXPECT_EQ(small.offset % 4096, 0u);
  for (const char* buffer : {"a", "b"}) {
    const auto& r = plan.resources[find_resource(plan, buffer)];
    const bool after = r.offset >= small.offset + 4096, before = r.offset + r.size <= small.offset;
    EXPECT_TRUE(after || before) << buffer;
  }
  expect_valid(graph, plan, memory);
}

TEST(Plan, OutputsStayAliveUntilTheEnd) {
  const rg::CompiledPlan plan = culled_branch_graph().compile(MockMemoryModel());
  const auto& luminance = plan.resources[find_resource(plan, "luminance")];
  EXPECT_EQ(luminance.last_pass, plan.passes.size() - 1);
}

TEST(Plan, SeveralReadsOfOneResourceInOnePassMerge) {
  rg::Graph graph;
  auto target = graph.import_texture("target", texture_desc(64, 64, VK_FORMAT_R8G8B8A8_UNORM),
                                     rg::ImportState::none(), rg::ImportState::of(Usage::Sampled));
  rg::BufferHandle args;
  graph.add_pass("build", QueueType::Compute, [&](PassBuilder& b) {
    args = b.write(b.create_buffer("args", {64}), Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("draw", QueueType::Graphics, [&](PassBuilder& b) {
    b.read(args, Usage::IndirectRead);
    b.read(args, Usage::StorageRead);
    target = b.write(target, Usage::ColorAttachment);
  }, no_execute);
  const MockMemoryModel memory;
  const rg::CompiledPlan plan = graph.compile(memory);
  ASSERT_EQ(graph.passes()[1].accesses.size(), 2u);
  const rg::Barrier& barrier = plan.passes[1].barriers[0];
  EXPECT_EQ(barrier.dst_stages, VK_PIPELINE_STAGE_2_DRAW_INDIRECT_BIT | VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT |
                                    VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  EXPECT_EQ(barrier.dst_access, VK_ACCESS_2_INDIRECT_COMMAND_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_READ_BIT);
  expect_valid(graph, plan, memory);
}

// A final read state must also order reads made in other stages: the next frame only
// waits on the final state's stages.
TEST(Plan, FinalReadStateOrdersReadsFromOtherStages) {
  rg::Graph graph;
  auto lut = graph.import_buffer("lut", {256}, rg::ImportState::of(Usage::TransferDst),
                                 rg::ImportState::of(Usage::UniformRead, QueueType::Compute));
  graph.add_pass("draw", QueueType::Graphics, [&](PassBuilder& b) {
    b.side_effect();
    b.read(lut, Usage::UniformRead);  // fragment/pre-raster, not in the final state's stages
  }, no_execute);
  const MockMemoryModel memory;
  const rg::CompiledPlan plan = graph.compile(memory);
  ASSERT_EQ(plan.final_barriers.size(), 1u);
  EXPECT_EQ(plan.final_barriers[0].src_stages & VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT,
            VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  expect_valid(graph, plan, memory);

  rg::CompiledPlan broken = plan;
  broken.final_barriers.clear();
  EXPECT_FALSE(verify_plan(graph, broken, memory).empty());
}

TEST(Plan, UnusedImportStillReachesItsFinalState) {
  rg::Graph graph;
  graph.import_texture("history", texture_desc(64, 64, VK_FORMAT_R8G8B8A8_UNORM), rg::ImportState::of(Usage::TransferDst),
                       rg::ImportState::of(Usage::Sampled));
  const MockMemoryModel memory;
  const rg::CompiledPlan plan = graph.compile(memory);
  ASSERT_EQ(plan.final_barriers.size(), 1u);
  EXPECT_EQ(plan.final_barriers[0].old_layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  EXPECT_EQ(plan.final_barriers[0].new_layout, VK_IMAGE_LAYOUT_SHADER_READ_ONLY_OPTIMAL);
  expect_valid(graph, plan, memory);
}

TEST(Plan, EmptyGraphCompiles) {
  const rg::Graph graph;
  const rg::CompiledPlan plan = graph.compile(MockMemoryModel());
  EXPECT_TRUE(plan.passes.empty());
  EXPECT_TRUE(plan.heaps.empty());
}

TEST(Plan, JsonDumpParsesAndMatchesThePlan) {
  const rg::CompiledPlan plan = culled_branch_graph().compile(MockMemoryModel());
  const auto json = nlohmann::json::parse(plan.to_json());
  ASSERT_EQ(json["passes"].size(), plan.passes.size());
  EXPECT_EQ(json["passes"][1]["name"], "main");
  EXPECT_EQ(json["passes"][1]["barriers"][0]["new_layout"], "DEPTH_STENCIL_READ_ONLY_OPTIMAL");
  EXPECT_EQ(json["culled_passes"].size(), 2u);
  EXPECT_EQ(json["resources"][find_resource(plan, "overlay")]["used"], false);
  EXPECT_EQ(json["stats"]["transient_bytes_aliased"], plan.stats.transient_bytes_aliased);
}

TEST(Plan, DotDumpShowsPassesResourcesEdgesAndCulling) {
  const rg::CompiledPlan plan = culled_branch_graph().compile(MockMemoryModel());
  const std::string dot = plan.to_dot();
  EXPECT_EQ(dot.rfind("digraph rendergraph {", 0), 0u);
  EXPECT_NE(dot.find("p0 [shape=box, label=\"depth_prepass\\ngraphics\"]"), std::string::npos) << dot;
  EXPECT_NE(dot.find("p3 [shape=box, label=\"debug_heatmap\\ncompute\", style=\"filled,dashed\""), std::string::npos)
      << dot;
  EXPECT_NE(dot.find("r1 [shape=ellipse, label=\"depth\\n512x512 D32_SFLOAT\\nheap 0 @ "), std::string::npos) << dot;
  EXPECT_NE(dot.find("p0 -> r1 [label=\"DepthAttachmentWrite\"]"), std::string::npos) << dot;  // write edge
  EXPECT_NE(dot.find("r1 -> p1 [label=\"DepthAttachmentRead\"]"), std::string::npos) << dot;   // read edge
}

}  // namespace
}  // namespace plan_test
}  // namespace rg_test
