#include <gtest/gtest.h>

#include <filesystem>

#include "gpu/barriers.h"
#include "gpu/pipeline.h"
#include "gpu/rendering.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "io/image_io.h"
#include "support/gpu_test.h"

namespace avsm {
namespace draw_test {  // one per file: test targets are unity builds
namespace {

using testing::GpuTest;

// Draws one red triangle over the left half of a cleared target and checks pixels,
// then writes the frame as PNG and EXR and reads both files back.
TEST_F(GpuTest, OffscreenDrawProducesExpectedPixels) {
  const uint32_t size = 64;
  gpu::ImageDesc desc;
  desc.width = desc.height = size;
  desc.format = VK_FORMAT_R16G16B16A16_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT;
  desc.name = "draw target";
  gpu::Image target = gpu::Image::create(ctx(), desc);

  gpu::GraphicsPipelineDesc pipeline_desc;
  pipeline_desc.name = "triangle";
  pipeline_desc.vertex = shaders().load("shaders/tests/triangle.vert");
  pipeline_desc.fragment = shaders().load("shaders/tests/triangle.frag");
  pipeline_desc.color_formats = {desc.format};
  gpu::Pipeline triangle = gpu::Pipeline::graphics(ctx(), pipeline_desc);

  ctx().submit_and_wait([&](VkCommandBuffer cmd) {
    gpu::ScopedLabel label(ctx(), cmd, "draw triangle");
    gpu::image_barrier(cmd, target.handle(), target.full_range(), VK_IMAGE_LAYOUT_UNDEFINED,
                       VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL, {}, gpu::kColorWrite);
    gpu::ColorTarget color{target.view()};
    color.clear = {{0.0f, 0.0f, 0.25f, 1.0f}};
    gpu::begin_rendering(cmd, {size, size}, {&color, 1});
    triangle.bind(cmd);
    vkCmdDraw(cmd, 3, 1, 0, 0);
    vkCmdEndRendering(cmd);
  });

  gpu::ImageRGBA32F frame = gpu::read_image(ctx(), target, VK_IMAGE_LAYOUT_COLOR_ATTACHMENT_OPTIMAL);
  ASSERT_EQ(frame.width, size);
  // The triangle covers x < size/2 near the bottom edge (y = -1 in clip space is the top row in Vulkan).
  const float* inside = frame.at(4, 4);
  const float* outside = frame.at(size - 4, size - 4);
  EXPECT_FLOAT_EQ(inside[0], 1.0f);
  EXPECT_FLOAT_EQ(inside[2], 0.0f);
  EXPECT_FLOAT_EQ(outside[0], 0.0f);
  EXPECT_FLOAT_EQ(outside[2], 0.25f);
  int covered = 0;
  for (uint32_t y = 0; y < size; ++y)
    for (uint32_t x = 0; x < size; ++x) covered += frame.at(x, y)[0] > 0.5f;
  // Half of the left half: a quarter of the target, give or take the diagonal's edge.
  EXPECT_NEAR(covered, size * size / 4, size);

  std::filesystem::path dir = std::filesystem::temp_directory_path() / "avsm_draw_test";
  std::filesystem::create_directories(dir);
  io::write_png_srgb(dir / "frame.png", frame);
  io::write_exr(dir / "frame.exr", frame);
  gpu::ImageRGBA32F png = io::read_png(dir / "frame.png");
  gpu::ImageRGBA32F exr = io::read_exr(dir / "frame.exr");
  EXPECT_FLOAT_EQ(png.at(4, 4)[0], 1.0f);
  EXPECT_NEAR(png.at(size - 4, size - 4)[2], io::linear_to_srgb(0.25f), 1.0f / 255.0f);
  EXPECT_FLOAT_EQ(exr.at(size - 4, size - 4)[2], 0.25f);
  EXPECT_FLOAT_EQ(exr.at(4, 4)[0], 1.0f);
}

}  // namespace
}  // namespace draw_test
}  // namespace avsm
