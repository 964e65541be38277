// The frame graph on a real device: a multi-pass graph (compute, graphics,
// sampled and storage images, buffers) that aliases transient memory, run under
// synchronization validation in every compile mode; the images must match.
#include <gtest/gtest.h>

#include <rendergraph/rendergraph.h>
#include <rendergraph/vulkan/executor.h>

#include "gpu/pipeline.h"
#include "gpu/rendering.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "support/gpu_test.h"
#include "tests/graph_fill.h"
#include "tests/graph_to_image.h"

namespace avsm {
namespace frame_graph_test {  // one per file: test targets are unity builds
namespace {

using testing::GpuTest;

constexpr uint32_t kSize = 64;

using FillPush = shared::GraphFillPush;
using ToImagePush = shared::GraphToImagePush;

struct Pipelines {
  gpu::Pipeline fill, to_image, combine, triangle;
  gpu::Sampler sampler;
};

Pipelines make_pipelines(gpu::Context& ctx, const gpu::ShaderLibrary& shaders) {
  Pipelines p;
  p.fill = gpu::Pipeline::compute(ctx, shaders.load("shaders/tests/graph_fill.comp"), "graph fill");
  p.to_image = gpu::Pipeline::compute(ctx, shaders.load("shaders/tests/graph_to_image.comp"), "graph to image");
  p.combine = gpu::Pipeline::compute(ctx, shaders.load("shaders/tests/graph_combine.comp"), "graph combine");
  gpu::GraphicsPipelineDesc triangle;
  triangle.name = "graph triangle";
  triangle.vertex = shaders.load("shaders/tests/triangle.vert");
  triangle.fragment = shaders.load("shaders/tests/triangle.frag");
  triangle.color_formats = {VK_FORMAT_R16G16B16A16_SFLOAT};
  p.triangle = gpu::Pipeline::graphics(ctx, triangle);
  p.sampler = gpu::Sampler(ctx, {VK_FILTER_NEAREST, VK_SAMPLER_MIPMAP_MODE_NEAREST});
  return p;
}

// Two "lights" each fill a transient buffer and spread it into a transient image;
// a draw renders into a transient colour target; a combine pass writes the imported
// result. The buffers of the two lights have disjoint lifetimes and can share memory.
// An unused pass is culled (or kept, with culling off).
rg::Graph build_graph(gpu::Context& ctx, Pipelines& p, rg::TextureHandle& result_out) {
  rg::Graph graph;
  rg::TextureDesc image_desc{kSize, kSize, 1, 1, 1, VK_FORMAT_R16G16B16A16_SFLOAT};
  rg::TextureHandle result = graph.import_texture("result", image_desc, rg::ImportState::none(),
                                                  rg::ImportState::of(rg::Usage::TransferSrc));
  rg::TextureHandle light_images[2];
  for (int light = 0; light < 2; ++light) {
    // Appending (not prepending to a temporary) keeps g++ 12 free of a false -Wrestrict.
    auto named = [light](const char* base) { return std::string(base).append(" ").append(std::to_string(light)); };
    struct Fill {
      rg::BufferHandle values;
    };
    const Fill& fill = graph.add_pass<Fill>(named("fill"), rg::QueueType::Compute,
        [&](rg::PassBuilder& b, Fill& d) {
          d.values = b.write(b.create_buffer(named("values"), {kSize * kSize * 4}), rg::Usage::StorageWrite);
        },
        [&ctx, &p, light](const Fill& d, rg::PassContext& c) {
          p.fill.bind(c.cmd());
          gpu::Bindings(ctx, p.fill).buffer("Values", c.buffer(d.values)).push(c.cmd());
          p.fill.push_constants(c.cmd(), FillPush{0.05f + 0.02f * light, 1.0f * light, kSize * kSize});
          p.fill.dispatch_threads(c.cmd(), kSize * kSize);
        });
    struct ToImage {
      rg::BufferHandle values;
      rg::TextureHandle image;
    };
    const ToImage& to_image = graph.add_pass<ToImage>(named("to image"), rg::QueueType::Compute,
        [&](rg::PassBuilder& b, ToImage& d) {
          d.values = b.read(fill.values, rg::Usage::StorageRead);
          d.image = b.write(b.create_texture(named("light image"), image_desc), rg::Usage::StorageWrite);
        },
        [&ctx, &p, light](const ToImage& d, rg::PassContext& c) {
          p.to_image.bind(c.cmd());
          gpu::Bindings(ctx, p.to_image)
              .buffer("Values", c.buffer(d.values))
              .image("target", c.view(d.image), c.layout(d.image))
              .push(c.cmd());
          ToImagePush push{{light == 0 ? 1.0f : 0.2f, 0.6f, light == 1 ? 1.0f : 0.3f, 0}, kSize, kSize};
          p.to_image.push_constants(c.cmd(), push);
          p.to_image.dispatch_threads(c.cmd(), kSize, kSize);
        });
    light_images[light] = to_image.image;
  }
  struct Draw {
    rg::TextureHandle target;
  };
  const Draw& draw = graph.add_pass<Draw>("draw", rg::QueueType::Graphics,
      [&](rg::PassBuilder& b, Draw& d) {
        d.target = b.write(b.create_texture("drawn", image_desc), rg::Usage::ColorAttachment);
      },
      [&p](const Draw& d, rg::PassContext& c) {
        gpu::ColorTarget color{c.view(d.target), c.layout(d.target), {{0.0f, 0.1f, 0.2f, 1.0f}}};
        gpu::begin_rendering(c.cmd(), {kSize, kSize}, {&color, 1});
        p.triangle.bind(c.cmd());
        vkCmdDraw(c.cmd(), 3, 1, 0, 0);
        vkCmdEndRendering(c.cmd());
      });
  struct Unused {};
  graph.add_pass<Unused>("unused", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Unused&) { b.write(b.create_buffer("unused scratch", {4096}), rg::Usage::TransferDst); },
      [](const Unused&, rg::PassContext&) {});
  struct Combine {
    rg::TextureHandle a, b, drawn, result;
  };
  const Combine& combine = graph.add_pass<Combine>("combine", rg::QueueType::Compute,
      [&](rg::PassBuilder& b, Combine& d) {
        d.a = b.read(light_images[0], rg::Usage::StorageRead);
        d.b = b.read(light_images[1], rg::Usage::StorageRead);
        d.drawn = b.read(draw.target, rg::Usage::Sampled);
        d.result = b.write(result, rg::Usage::StorageWrite);
      },
      [&ctx, &p](const Combine& d, rg::PassContext& c) {
        p.combine.bind(c.cmd());
        gpu::Bindings(ctx, p.combine)
            .image("a", c.view(d.a), c.layout(d.a))
            .image("b", c.view(d.b), c.layout(d.b))
            .image("drawn", c.view(d.drawn), c.layout(d.drawn), p.sampler.handle())
            .image("result", c.view(d.result), c.layout(d.result))
            .push(c.cmd());
        p.combine.dispatch_threads(c.cmd(), kSize, kSize);
      });
  result_out = combine.result;
  return graph;
}

struct FrameResult {
  gpu::ImageRGBA32F pixels;
  rg::PlanStats stats;
  size_t passes_run = 0;
  bool reused = false;
};

FrameResult run_frame(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const rg::CompileOptions& options,
                      int frames = 1) {
  Pipelines pipelines = make_pipelines(ctx, shaders);
  gpu::ImageDesc result_desc;
  result_desc.width = result_desc.height = kSize;
  result_desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  result_desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  result_desc.name = "graph result";
  gpu::Image result_image = gpu::Image::create(ctx, result_desc);
  rg::vulkan::Executor executor(ctx, gpu::TimestampMode::Exact);
  FrameResult out;
  for (int frame = 0; frame < frames; ++frame) {
    rg::TextureHandle result;
    rg::Graph graph = build_graph(ctx, pipelines, result);
    executor.bind(result, result_image);
    ctx.submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd, options); });
    out.reused = executor.plan_was_reused();
  }
  out.pixels = gpu::read_image(ctx, result_image, VK_IMAGE_LAYOUT_TRANSFER_SRC_OPTIMAL);
  out.stats = executor.plan().stats;
  out.passes_run = executor.plan().passes.size();
  return out;
}

TEST_F(GpuTest, FrameGraphImagesMatchInEveryMode) {
  FrameResult normal = run_frame(ctx(), shaders(), {});
  EXPECT_EQ(normal.passes_run, 6u) << "the unused pass should be culled";
  EXPECT_LT(normal.stats.transient_bytes_aliased, normal.stats.transient_bytes_unaliased)
      << "the two lights' buffers should share memory";

  // The picture is what the passes computed: triangle red over the left half,
  // combined with the two light images.
  const float* top_left = normal.pixels.at(2, 2);
  EXPECT_GT(top_left[0], 0.5f);

  rg::CompileOptions no_aliasing;
  no_aliasing.aliasing = false;
  FrameResult unaliased = run_frame(ctx(), shaders(), no_aliasing);
  EXPECT_EQ(unaliased.stats.transient_bytes_aliased, unaliased.stats.transient_bytes_unaliased);
  EXPECT_EQ(normal.pixels.pixels, unaliased.pixels.pixels);

  rg::CompileOptions no_culling;
  no_culling.culling = false;
  FrameResult unculled = run_frame(ctx(), shaders(), no_culling);
  EXPECT_EQ(unculled.passes_run, 7u);
  EXPECT_EQ(normal.pixels.pixels, unculled.pixels.pixels);

  rg::CompileOptions serial;
  serial.serial_full_barriers = true;
  FrameResult serial_result = run_frame(ctx(), shaders(), serial);
  EXPECT_EQ(normal.pixels.pixels, serial_result.pixels.pixels);
}

TEST_F(GpuTest, FrameGraphReusesThePlanWhenTheShapeIsUnchanged) {
  FrameResult twice = run_frame(ctx(), shaders(), {}, 2);
  EXPECT_TRUE(twice.reused);
  FrameResult once = run_frame(ctx(), shaders(), {}, 1);
  EXPECT_FALSE(once.reused);
  EXPECT_EQ(twice.pixels.pixels, once.pixels.pixels);
}

TEST_F(GpuTest, FrameGraphRejectsAnUnboundImport) {
  Pipelines pipelines = make_pipelines(ctx(), shaders());
  rg::TextureHandle result;
  rg::Graph graph = build_graph(ctx(), pipelines, result);
  rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
  VkCommandBuffer cmd = ctx().allocate_command_buffer("unbound import");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  vkBeginCommandBuffer(cmd, &begin);
  try {
    executor.record(graph, cmd);
    FAIL() << "expected an error";
  } catch (const rg::GraphError& e) {
    EXPECT_NE(std::string(e.what()).find("'result'"), std::string::npos) << e.what();
  }
  vkEndCommandBuffer(cmd);
  vkFreeCommandBuffers(ctx().device(), ctx().command_pool(), 1, &cmd);
}


// The timer has room for any number of passes: a graph of more passes than the executor
// was first made for (and more than the 512 it once stopped at) is timed pass by pass, as a
// scene of 200 shadowed lights needs.
TEST_F(GpuTest, FrameGraphTimesEveryPassOfALargeGraph) {
  gpu::Buffer target = gpu::Buffer::create(ctx(), {256, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                                   gpu::MemoryLocation::DeviceLocal, "timed passes target"});
  rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact, /*timed_passes=*/1);
  for (uint32_t passes : {600u, 3u, 700u}) {
    rg::Graph graph;
    const rg::ImportState written = rg::ImportState::of(rg::Usage::TransferDst);
    rg::BufferHandle buffer = rg::vulkan::import(graph, "target", target, rg::ImportState::none(), written);
    for (uint32_t p = 0; p < passes; ++p) {
      struct Data {
        rg::BufferHandle buffer;
      };
      buffer = graph.add_pass<Data>("fill " + std::to_string(p), rg::QueueType::Transfer,
          [&](rg::PassBuilder& b, Data& d) { d.buffer = b.write(buffer, rg::Usage::TransferDst); },
          [p](const Data& d, rg::PassContext& c) {
            const gpu::BufferRange range = c.buffer(d.buffer);
            vkCmdFillBuffer(c.cmd(), range, range.offset, 4, p);
          })
          .buffer;
    }
    ctx().submit_and_wait([&](VkCommandBuffer cmd) { executor.record(graph, cmd); });
    const std::vector<rg::vulkan::PassTiming> timings = executor.read_timings();
    ASSERT_EQ(timings.size(), passes);
    EXPECT_EQ(timings.back().name, "fill " + std::to_string(passes - 1));
  }
}

}  // namespace
}  // namespace frame_graph_test
}  // namespace avsm
