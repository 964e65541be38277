// The pass list made from frame-graph declarations, and add_to_graph made from the list,
// without a device: a small graph of the shapes the shadow passes declare (an imported
// buffer, a transient image cleared then read and written in place, a transient buffer
// written by ranges, a side effect) goes to a list and back into a graph, which must
// declare the same passes, resources and accesses.
#include <gtest/gtest.h>

#include <algorithm>
#include <string>
#include <vector>

#include <rendergraph/graph.h>

#include "avsm/shadows_rendergraph.h"
#include "gpu/resources.h"
#include "passes/shadows/shadow_pass_list_builder.h"

namespace avsm {
namespace pass_list_test {  // one per file: test targets are unity builds
namespace {

struct Declaration {
  rg::Graph graph;
  gpu::Buffer counter;  // no device: an empty buffer, the import's physical resource
};

void declare(Declaration& d) {
  rg::Graph& graph = d.graph;
  rg::BufferHandle counter = graph.import_buffer("counter", {16}, rg::ImportState::none(),
                                                 rg::ImportState::of(rg::Usage::HostRead),
                                                 static_cast<const gpu::Buffer*>(&d.counter));
  rg::TextureHandle heads;
  rg::BufferHandle nodes;
  graph.add_pass("clear", rg::QueueType::Graphics, [&](rg::PassBuilder& b) {
    heads = b.write(b.create_texture("heads", {8, 8, 1, 1, 1, VK_FORMAT_R32_UINT, "resolution"}), rg::Usage::TransferDst);
    nodes = b.write(b.create_buffer("nodes", {1024}), rg::Usage::TransferDst, {0, 512});
    counter = b.write(counter, rg::Usage::TransferDst);
  }, {});
  graph.add_pass("capture", rg::QueueType::Compute, [&](rg::PassBuilder& b) {
    heads = b.read_write(heads, rg::Usage::StorageReadWrite);
    nodes = b.read(nodes, rg::Usage::StorageRead, {0, 512});
    nodes = b.write(nodes, rg::Usage::StorageWrite, {512, 512});
    b.read_write(counter, rg::Usage::StorageReadWrite);
    b.side_effect();
  }, {});
}

TEST(ShadowPassList, ListsTheDeclarationsInTheUsageTablesTerms) {
  Declaration d;
  declare(d);
  const ShadowPassList list = passes::pass_list_of(d.graph, nullptr);
  ASSERT_EQ(list.resources.size(), 3u);
  const PassResource& counter = list.resources[0];
  EXPECT_FALSE(counter.transient);
  EXPECT_EQ(counter.final_state.stages, VK_PIPELINE_STAGE_2_HOST_BIT);
  EXPECT_EQ(counter.final_state.access, VK_ACCESS_2_HOST_READ_BIT);
  const PassResource& heads = list.resources[1];
  EXPECT_TRUE(heads.transient);
  EXPECT_EQ(heads.kind, PassResource::Kind::image);
  EXPECT_EQ(heads.image.format, VK_FORMAT_R32_UINT);
  EXPECT_EQ(heads.image.usage, VkImageUsageFlags(VK_IMAGE_USAGE_TRANSFER_DST_BIT | VK_IMAGE_USAGE_STORAGE_BIT));
  EXPECT_EQ(heads.sized_by, "resolution");
  EXPECT_EQ(list.resources[2].buffer.size, 1024u);
  EXPECT_EQ(list.resources[2].buffer.usage,
            VkBufferUsageFlags(VK_BUFFER_USAGE_TRANSFER_DST_BIT | VK_BUFFER_USAGE_STORAGE_BUFFER_BIT));

  ASSERT_EQ(list.passes.size(), 2u);
  EXPECT_EQ(list.passes[0].queue, PassQueue::graphics);
  const PassResourceUse& clear_heads = list.passes[0].uses[0];
  EXPECT_TRUE(clear_heads.writes && !clear_heads.reads);
  EXPECT_EQ(clear_heads.layout, VK_IMAGE_LAYOUT_TRANSFER_DST_OPTIMAL);
  EXPECT_EQ(clear_heads.stages, VK_PIPELINE_STAGE_2_TRANSFER_BIT);
  EXPECT_EQ(clear_heads.usages, std::vector<std::string>{"TransferDst"});
  const ShadowPass& capture = list.passes[1];
  EXPECT_TRUE(capture.side_effect);
  ASSERT_EQ(capture.uses.size(), 4u);  // heads, the two ranges of nodes, counter
  EXPECT_EQ(capture.uses[0].layout, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(capture.uses[0].stages, VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT);
  EXPECT_EQ(capture.uses[0].access, VK_ACCESS_2_SHADER_STORAGE_READ_BIT | VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT);
  EXPECT_EQ(capture.uses[2].offset, 512u);
  EXPECT_EQ(capture.uses[2].size, 512u);
  EXPECT_TRUE(capture.uses[2].writes && !capture.uses[2].reads);

  // Without a device the list can be looked at, not recorded.
  EXPECT_THROW(capture.record(VK_NULL_HANDLE, {}), std::logic_error);
}

TEST(ShadowPassList, AddToGraphDeclaresWhatTheListSays) {
  Declaration d;
  declare(d);
  rg::Graph again;
  add_to_graph(again, passes::pass_list_of(d.graph, nullptr));
  ASSERT_EQ(again.passes().size(), d.graph.passes().size());
  for (size_t p = 0; p < again.passes().size(); ++p) {
    const rg::PassDecl &want = d.graph.passes()[p], &got = again.passes()[p];
    EXPECT_EQ(got.name, want.name);
    EXPECT_EQ(got.queue, want.queue);
    EXPECT_EQ(got.side_effect, want.side_effect);
    ASSERT_EQ(got.accesses.size(), want.accesses.size()) << want.name;
    for (size_t a = 0; a < got.accesses.size(); ++a) {
      const rg::AccessDecl &w = want.accesses[a], &g = got.accesses[a];
      EXPECT_EQ(again.resources()[g.resource].name, d.graph.resources()[w.resource].name) << want.name;
      EXPECT_EQ(g.range, w.range) << want.name;
      EXPECT_EQ(g.usages, w.usages) << want.name;
      EXPECT_EQ(g.reads, w.reads) << want.name;
      EXPECT_EQ(g.writes, w.writes) << want.name;
    }
  }
  ASSERT_EQ(again.resources().size(), d.graph.resources().size());
  for (const rg::ResourceDecl& got : again.resources()) {
    const auto want = std::find_if(d.graph.resources().begin(), d.graph.resources().end(),
                                   [&](const rg::ResourceDecl& r) { return r.name == got.name; });
    ASSERT_NE(want, d.graph.resources().end()) << got.name;
    EXPECT_EQ(got.imported, want->imported) << got.name;
    EXPECT_EQ(got.texture, want->texture) << got.name;
    EXPECT_EQ(got.buffer, want->buffer) << got.name;
    EXPECT_EQ(got.initial, want->initial) << got.name;
    EXPECT_EQ(got.final_state, want->final_state) << got.name;
  }
}

}  // namespace
}  // namespace pass_list_test
}  // namespace avsm
