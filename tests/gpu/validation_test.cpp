#include <gtest/gtest.h>

#include "gpu/barriers.h"
#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "support/gpu_test.h"

namespace avsm {
namespace validation_test {  // one per file: test targets are unity builds
namespace {

using testing::FillPush;
using testing::GpuTest;

// A compute shader writes a buffer and a copy reads it. With `with_barrier`
// false the copy races the shader: exactly what synchronization validation exists to catch.
void write_then_copy(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, bool with_barrier) {
  const uint32_t count = 256;
  gpu::Buffer values = gpu::Buffer::create(
      ctx, {count * 4, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_SRC_BIT,
            gpu::MemoryLocation::DeviceLocal, "hazard values"});
  gpu::Buffer copy = gpu::Buffer::create(ctx, {count * 4, VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                               gpu::MemoryLocation::DeviceLocal, "hazard copy"});
  gpu::Pipeline fill = gpu::Pipeline::compute(ctx, shaders.load("shaders/tests/fill.comp"), "fill");
  ctx.submit_and_wait([&](VkCommandBuffer cmd) {
    fill.bind(cmd);
    gpu::Bindings(ctx, fill).buffer("Values", values).push(cmd);
    fill.push_constants(cmd, FillPush{1.0f, 0.0f, count});
    fill.dispatch_threads(cmd, count);
    if (with_barrier) gpu::buffer_barrier(cmd, values.handle(), gpu::kComputeWrite, gpu::kTransferRead);
    VkBufferCopy region{0, 0, count * 4};
    vkCmdCopyBuffer(cmd, values.handle(), copy.handle(), 1, &region);
  });
}

TEST_F(GpuTest, MissingBarrierIsCaughtBySyncValidation) {
  write_then_copy(ctx(), shaders(), /*with_barrier=*/false);
  std::vector<gpu::ValidationMessage> messages = take_validation_messages();
  ASSERT_FALSE(messages.empty()) << "the missing barrier went unnoticed: the harness cannot fail";
  bool found = false;
  for (const gpu::ValidationMessage& m : messages) {
    if (m.id_name == "SYNC-HAZARD-READ-AFTER-WRITE") {
      found = true;
      // Debug-utils names reach the message, so a real failure is readable.
      EXPECT_NE(m.text.find("hazard values"), std::string::npos) << m.text;
    }
  }
  EXPECT_TRUE(found) << gpu::describe(messages);
}

TEST_F(GpuTest, SameWorkWithTheBarrierIsClean) {
  write_then_copy(ctx(), shaders(), /*with_barrier=*/true);
  // TearDown fails the test on any message.
}

TEST_F(GpuTest, ApiMisuseIsCaughtByCoreValidation) {
  // A zero-sized copy is invalid usage (VUID-VkBufferCopy-size-01988).
  gpu::Buffer a = gpu::Buffer::create(ctx(), {64, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                              gpu::MemoryLocation::DeviceLocal, "misuse a"});
  gpu::Buffer b = gpu::Buffer::create(ctx(), {64, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                                              gpu::MemoryLocation::DeviceLocal, "misuse b"});
  ctx().submit_and_wait([&](VkCommandBuffer cmd) {
    VkBufferCopy region{0, 0, 0};
    vkCmdCopyBuffer(cmd, a.handle(), b.handle(), 1, &region);
  });
  std::vector<gpu::ValidationMessage> messages = take_validation_messages();
  ASSERT_FALSE(messages.empty());
  EXPECT_NE(messages[0].id_name.find("VUID-VkBufferCopy-size"), std::string::npos) << gpu::describe(messages);
}

}  // namespace
}  // namespace validation_test
}  // namespace avsm
