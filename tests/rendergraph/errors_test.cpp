// Misuse is refused with a GraphError naming the pass and the resource: at the call for
// handle problems (only the call knows which version it was given), at compile time for
// problems with the declaration as a whole.
#include <gtest/gtest.h>

#include <rendergraph/graph.h>

#include "mock_memory_model.h"
#include "test_graphs.h"

namespace rg_test {
namespace errors_test {  // one per file: test targets are unity builds
namespace {

using rg::PassBuilder;
using rg::QueueType;
using rg::Usage;

// Runs `fn`, expects a GraphError, returns its message ("" and a failure otherwise).
template <class Fn>
std::string error_of(Fn&& fn) {
  try {
    fn();
  } catch (const rg::GraphError& error) {
    return error.what();
  }
  ADD_FAILURE() << "expected a GraphError";
  return "";
}

std::string compile_error(const rg::Graph& graph) {
  return error_of([&] { graph.compile(MockMemoryModel()); });
}

const rg::TextureDesc kColor = texture_desc(64, 64, VK_FORMAT_R8G8B8A8_UNORM);

TEST(Errors, StaleHandleNamesPassResourceAndVersions) {
  rg::Graph graph;
  rg::BufferHandle nodes;
  graph.add_pass("capture", QueueType::Graphics, [&](PassBuilder& b) {
    nodes = b.write(b.create_buffer("avsm_nodes", {1024}), Usage::StorageWrite);  // version 1
  }, no_execute);
  graph.add_pass("sort", QueueType::Compute, [&](PassBuilder& b) {
    b.read_write(nodes, Usage::StorageReadWrite);  // makes version 2, result dropped
  }, no_execute);
  const std::string message = error_of([&] {
    graph.add_pass("shade", QueueType::Graphics, [&](PassBuilder& b) { b.read(nodes, Usage::StorageRead); }, no_execute);
  });
  EXPECT_EQ(message, "pass 'shade': stale handle to 'avsm_nodes' (version 1, current 2)");
}

TEST(Errors, HandleFromAnotherGraph) {
  rg::Graph first, second;
  auto history = first.import_texture("history", kColor, rg::ImportState::of(Usage::Sampled),
                                      rg::ImportState::of(Usage::Sampled));
  const std::string message = error_of([&] {
    second.add_pass("taa", QueueType::Compute, [&](PassBuilder& b) { b.read(history, Usage::Sampled); }, no_execute);
  });
  EXPECT_NE(message.find("pass 'taa': handle to resource #0 belongs to another graph"), std::string::npos) << message;
}

TEST(Errors, DefaultConstructedHandle) {
  rg::Graph graph;
  const std::string message = error_of([&] {
    graph.add_pass("blit", QueueType::Transfer, [&](PassBuilder& b) { b.read(rg::BufferHandle{}, Usage::TransferSrc); },
                   no_execute);
  });
  EXPECT_EQ(message, "pass 'blit': invalid (default-constructed) buffer handle");
}

TEST(Errors, ForgedHandleOfTheWrongKind) {
  rg::Graph graph;
  auto buffer = graph.import_buffer("counts", {64}, rg::ImportState::none(), rg::ImportState::none());
  const rg::TextureHandle forged{buffer.index, 0, buffer.graph_id};
  const std::string message = error_of([&] {
    graph.add_pass("p", QueueType::Compute, [&](PassBuilder& b) { b.read(forged, Usage::Sampled); }, no_execute);
  });
  EXPECT_EQ(message, "pass 'p': 'counts' is a buffer, not a texture");
}

TEST(Errors, ReadingANeverWrittenTransient) {
  rg::Graph graph;
  graph.add_pass("use", QueueType::Compute, [&](PassBuilder& b) {
    b.side_effect();
    b.read(b.create_texture("gbuffer_normal", kColor), Usage::Sampled);
  }, no_execute);
  EXPECT_EQ(compile_error(graph), "pass 'use': 'gbuffer_normal': read before any pass wrote it");
}

TEST(Errors, ReadingAnImportWithUndefinedContents) {
  rg::Graph graph;
  auto target = graph.import_texture("target", kColor, rg::ImportState::none(), rg::ImportState::none());
  graph.add_pass("post", QueueType::Compute, [&](PassBuilder& b) {
    b.side_effect();
    b.read(target, Usage::Sampled);
  }, no_execute);
  EXPECT_EQ(compile_error(graph),
            "pass 'post': 'target': read, but the imported contents are undefined (initial layout UNDEFINED)");
}

TEST(Errors, DuplicateResourceNames) {
  rg::Graph graph;
  graph.add_pass("a", QueueType::Compute, [&](PassBuilder& b) {
    b.write(b.create_buffer("scratch", {64}), Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("b", QueueType::Compute, [&](PassBuilder& b) {
    b.write(b.create_buffer("scratch", {64}), Usage::StorageWrite);
  }, no_execute);
  EXPECT_EQ(compile_error(graph),
            "duplicate resource name 'scratch' (created by pass 'a', and created by pass 'b')");
}

TEST(Errors, DuplicatePassNames) {
  rg::Graph graph;
  graph.add_pass("blur", QueueType::Compute, nullptr, no_execute);
  graph.add_pass("blur", QueueType::Compute, nullptr, no_execute);
  EXPECT_EQ(compile_error(graph), "duplicate pass name 'blur' (passes #0 and #1)");
}

TEST(Errors, UsageTheQueueCannotExecute) {
  rg::Graph graph;
  graph.add_pass("cs", QueueType::Compute, [&](PassBuilder& b) {
    b.write(b.create_texture("rt", kColor), Usage::ColorAttachment);
  }, no_execute);
  EXPECT_EQ(compile_error(graph), "pass 'cs': 'rt': usage ColorAttachment is not available in a compute pass");
}

TEST(Errors, UsageOnTheWrongKindOfResource) {
  rg::Graph buffers;
  buffers.add_pass("p", QueueType::Graphics, [&](PassBuilder& b) {
    b.write(b.create_buffer("b", {64}), Usage::ColorAttachment);
  }, no_execute);
  EXPECT_EQ(compile_error(buffers), "pass 'p': 'b': usage ColorAttachment is for textures only");

  rg::Graph uniform_texture;
  auto imported = uniform_texture.import_texture("lut", kColor, rg::ImportState::of(Usage::Sampled),
                                                 rg::ImportState::of(Usage::Sampled));
  uniform_texture.add_pass("p", QueueType::Graphics, [&](PassBuilder& b) {
    b.side_effect();
    b.read(imported, Usage::UniformRead);
  }, no_execute);
  EXPECT_EQ(compile_error(uniform_texture), "pass 'p': 'lut': usage UniformRead is for buffers only");
}

TEST(Errors, PresentIsNotAPassUsage) {
  rg::Graph graph;
  auto swapchain = graph.import_texture("swapchain", kColor, rg::ImportState::of(Usage::ColorAttachment),
                                        rg::ImportState::of(Usage::Present));
  graph.add_pass("p", QueueType::Graphics, [&](PassBuilder& b) {
    b.side_effect();
    b.read(swapchain, Usage::Present);
  }, no_execute);
  EXPECT_EQ(compile_error(graph), "pass 'p': 'swapchain': usage Present is only valid as an import state, not in a pass");
}

TEST(Errors, ReadWithAWritingUsageAndWriteWithAReadingUsage) {
  rg::Graph graph;
  rg::BufferHandle buffer;
  graph.add_pass("make", QueueType::Compute, [&](PassBuilder& b) {
    buffer = b.write(b.create_buffer("data", {64}), Usage::StorageWrite);
  }, no_execute);
  EXPECT_EQ(error_of([&] {
              graph.add_pass("r", QueueType::Compute, [&](PassBuilder& b) { b.read(buffer, Usage::StorageWrite); },
                             no_execute);
            }),
            "pass 'r': read() of 'data' with usage StorageWrite, which writes; use write() or read_write()");
  EXPECT_EQ(error_of([&] {
              graph.add_pass("w", QueueType::Compute, [&](PassBuilder& b) { b.write(buffer, Usage::StorageRead); },
                             no_execute);
            }),
            "pass 'w': write of 'data' with usage StorageRead, which only reads; use read()");
}

TEST(Errors, ConflictingLayoutsInOnePass) {
  rg::Graph graph;
  rg::TextureHandle image;
  graph.add_pass("make", QueueType::Compute, [&](PassBuilder& b) {
    image = b.write(b.create_texture("image", kColor), Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("use", QueueType::Compute, [&](PassBuilder& b) {
    b.side_effect();
    b.read(image, Usage::Sampled);      // SHADER_READ_ONLY_OPTIMAL
    b.read(image, Usage::StorageRead);  // GENERAL
  }, no_execute);
  EXPECT_EQ(compile_error(graph), "pass 'use': 'image': usages need different layouts in the same pass");
}

TEST(Errors, UsingAResourceAgainAfterWritingItInTheSamePass) {
  rg::Graph graph;
  const std::string message = error_of([&] {
    graph.add_pass("p", QueueType::Compute, [&](PassBuilder& b) {
      auto v1 = b.write(b.create_buffer("data", {64}), Usage::StorageWrite);
      b.read(v1, Usage::StorageRead);
    }, no_execute);
  });
  EXPECT_EQ(message, "pass 'p': uses 'data' again after writing it; a pass writes a resource once (use read_write())");
}

TEST(Errors, MarkOutputChecksItsHandle) {
  rg::Graph graph;
  rg::BufferHandle v1, created;
  graph.add_pass("a", QueueType::Compute, [&](PassBuilder& b) {
    created = b.create_buffer("histogram", {64});
    v1 = b.write(created, Usage::StorageWrite);
  }, no_execute);
  graph.add_pass("b", QueueType::Compute, [&](PassBuilder& b) { b.read_write(v1, Usage::StorageReadWrite); },
                 no_execute);
  EXPECT_EQ(error_of([&] { graph.mark_output(v1); }), "mark_output: stale handle to 'histogram' (version 1, current 2)");

  rg::Graph unwritten;
  rg::BufferHandle never;
  unwritten.add_pass("a", QueueType::Compute, [&](PassBuilder& b) { never = b.create_buffer("never", {64}); },
                     no_execute);
  unwritten.mark_output(never);
  EXPECT_EQ(compile_error(unwritten), "mark_output: 'never' was never written");
}

TEST(Errors, BadDescriptions) {
  rg::Graph graph;
  graph.add_pass("a", QueueType::Compute, [&](PassBuilder& b) {
    b.write(b.create_buffer("empty", {0}), Usage::StorageWrite);
  }, no_execute);
  EXPECT_EQ(compile_error(graph), "buffer 'empty' has size 0");

  rg::Graph formatless;
  formatless.add_pass("a", QueueType::Compute, [&](PassBuilder& b) {
    b.write(b.create_texture("t", rg::TextureDesc{.width = 4, .height = 4}), Usage::StorageWrite);
  }, no_execute);
  EXPECT_EQ(compile_error(formatless), "texture 't' has no format");
}

TEST(Errors, MemoryModelWithoutAMemoryType) {
  struct NoMemory : MockMemoryModel {
    rg::MemoryRequirements buffer(const rg::BufferDesc&, rg::UsageSet, const std::string&) const override {
      return {64, 16, 0};
    }
  };
  const rg::Graph graph = buffer_raw_graph();
  EXPECT_EQ(error_of([&] { graph.compile(NoMemory()); }),
            "memory model: no memory type for 'instances' (memory_type_bits 0)");
}

}  // namespace
}  // namespace errors_test
}  // namespace rg_test
