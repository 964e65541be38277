#include "support/gpu_test.h"

#include <cstdlib>
#include <memory>

namespace avsm::testing {

gpu::Context& test_context() {
  // Validation is not optional in tests, whatever the environment says.
  static std::unique_ptr<gpu::Context> ctx = [] {
    setenv("AVSM_VALIDATION", "1", 1);
    gpu::ContextDesc desc;
    desc.app_name = "avsm-tests";
    desc.validation = true;
    return std::make_unique<gpu::Context>(desc);
  }();
  return *ctx;
}

const gpu::ShaderLibrary& test_shaders() {
  static gpu::ShaderLibrary library;
  return library;
}

void GpuTest::SetUp() {
  ASSERT_TRUE(ctx().validation_enabled()) << "GPU tests must run under VK_LAYER_KHRONOS_validation";
  // Messages left by an earlier test belong to that test, which already failed.
  ctx().validation_log().take();
}

void GpuTest::TearDown() {
  vkDeviceWaitIdle(ctx().device());
  std::vector<gpu::ValidationMessage> messages = ctx().validation_log().take();
  EXPECT_TRUE(messages.empty()) << gpu::describe(messages);
}

std::vector<gpu::ValidationMessage> GpuTest::take_validation_messages() {
  vkDeviceWaitIdle(ctx().device());
  return ctx().validation_log().take();
}

}  // namespace avsm::testing
