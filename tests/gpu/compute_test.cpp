#include <gtest/gtest.h>

#include "gpu/barriers.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "support/gpu_test.h"

namespace avsm {
namespace compute_test {  // one per file: test targets are unity builds
namespace {

using testing::FillPush;
using testing::GpuTest;

TEST_F(GpuTest, ComputeDispatchWritesExpectedValues) {
  const uint32_t count = 1000;  // not a multiple of the workgroup size
  gpu::Buffer values = gpu::Buffer::create(
      ctx(), {count * sizeof(float), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
              gpu::MemoryLocation::DeviceLocal, "fill values"});
  gpu::Pipeline fill = gpu::Pipeline::compute(ctx(), shaders().load("shaders/tests/fill.comp"), "fill");
  ASSERT_EQ(fill.bindings().size(), 1u);
  EXPECT_EQ(fill.bindings()[0].type, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
  EXPECT_EQ(fill.local_size()[0], 64u);

  ctx().submit_and_wait([&](VkCommandBuffer cmd) {
    fill.bind(cmd);
    gpu::Bindings(ctx(), fill).buffer("Values", values).push(cmd);
    fill.push_constants(cmd, FillPush{0.5f, 3.0f, count});
    fill.dispatch_threads(cmd, count);
  });
  std::vector<float> out = gpu::read_buffer<float>(ctx(), values);
  ASSERT_EQ(out.size(), count);
  for (uint32_t i = 0; i < count; ++i) ASSERT_FLOAT_EQ(out[i], i * 0.5f + 3.0f) << "at " << i;
}

TEST_F(GpuTest, BindingTheWrongKindOfResourceIsAClearError) {
  gpu::Pipeline fill = gpu::Pipeline::compute(ctx(), shaders().load("shaders/tests/fill.comp"), "fill");
  gpu::Bindings bindings(ctx(), fill);
  EXPECT_THROW(bindings.image("Values", VK_NULL_HANDLE, VK_IMAGE_LAYOUT_GENERAL), gpu::InterfaceError);
  EXPECT_THROW(bindings.buffer("Missing", VK_NULL_HANDLE), gpu::InterfaceError);
}

}  // namespace
}  // namespace compute_test
}  // namespace avsm
