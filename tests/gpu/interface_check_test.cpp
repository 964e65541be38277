// Pipeline creation checks the structs C++ and GLSL share against SPIR-V reflection,
// and Bindings checks what is bound against the shaders' names, types and sizes.
#include <gtest/gtest.h>

#include <string>

#include "gpu/pipeline.h"
#include "gpu/resources.h"
#include "shared/lights.h"
#include "shared/passes/camera/volumes/volume_lighting_cache.h"
#include "support/gpu_test.h"
#include "tests/graph_fill.h"
#include "tests/misaligned.h"

namespace avsm {
namespace interface_check_test {  // one per file: test targets are unity builds
namespace {

using testing::GpuTest;

// The InterfaceError creating `shader` throws ("" when it does not throw).
std::string interface_error(gpu::Context& ctx, const gpu::ShaderLibrary& shaders, const std::string& shader) {
  try {
    gpu::Pipeline::compute(ctx, shaders.load(shader), "interface test");
  } catch (const gpu::InterfaceError& e) {
    return e.what();
  }
  return "";
}

TEST_F(GpuTest, AMisplacedPushConstantMemberIsCaughtAtPipelineCreation) {
  static_assert(offsetof(shared::MisalignedPush, direction) == 4, "GLM packs the vec3 after the float");
  const std::string error = interface_error(ctx(), shaders(), "shaders/tests/misaligned_push.comp");
  EXPECT_NE(error.find("shader 'shaders/tests/misaligned_push.comp'"), std::string::npos) << error;
  EXPECT_NE(error.find("struct MisalignedPush member 1 'direction' is at byte 16 in the shader and 4 in C++"),
            std::string::npos)
      << error;
  EXPECT_NE(error.find("tests/misaligned.h"), std::string::npos) << error;
}

TEST_F(GpuTest, AStaleCopyOfASharedStructIsCaughtAtPipelineCreation) {
  ASSERT_NE(gpu::find_struct_layout("GpuLight"), nullptr);  // registered by shared/lights.h
  const std::string error = interface_error(ctx(), shaders(), "shaders/tests/stale_light.comp");
  EXPECT_NE(error.find("shader 'shaders/tests/stale_light.comp'"), std::string::npos) << error;
  EXPECT_NE(error.find("struct GpuLight has 2 members in the shader and 4 in C++"), std::string::npos) << error;
}

TEST_F(GpuTest, PushConstantsWithoutACppDeclarationAreRefused) {
  const std::string error = interface_error(ctx(), shaders(), "shaders/tests/undeclared_push.comp");
  EXPECT_NE(error.find("push-constant block 'Push' has no C++ declaration"), std::string::npos) << error;
}

TEST_F(GpuTest, SharedStructsMatchTheirShaders) {
  EXPECT_EQ(interface_error(ctx(), shaders(), "shaders/tests/graph_fill.comp"), "");
  EXPECT_EQ(interface_error(ctx(), shaders(), "shaders/passes/camera/volumes/volume_lighting_cache.comp"), "");
}

TEST_F(GpuTest, PushingAnotherStructIsRefused) {
  gpu::Pipeline fill = gpu::Pipeline::compute(ctx(), shaders().load("shaders/tests/fill.comp"), "fill");
  ctx().submit_and_wait([&](VkCommandBuffer cmd) {
    fill.bind(cmd);
    EXPECT_THROW(fill.push_constants(cmd, shared::GraphFillPush{1.0f, 0.0f, 1u}), gpu::InterfaceError);
  });
}

TEST_F(GpuTest, BindingsAreCheckedByName) {
  gpu::Pipeline fill = gpu::Pipeline::compute(ctx(), shaders().load("shaders/tests/fill.comp"), "fill");
  gpu::Buffer values = gpu::Buffer::create(
      ctx(), {64, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryLocation::DeviceLocal, "values"});
  gpu::Bindings bindings(ctx(), fill);
  EXPECT_NO_THROW(bindings.buffer("Values", values));
  try {
    bindings.buffer("Values", gpu::BufferRange(values.handle(), 2));
    ADD_FAILURE() << "a buffer smaller than one element was accepted";
  } catch (const gpu::InterfaceError& e) {
    EXPECT_NE(std::string(e.what()).find("binding 'Values' (0) needs at least 4 bytes, the buffer given has 2"),
              std::string::npos)
        << e.what();
  }
  EXPECT_THROW(bindings.buffer("values", values), gpu::InterfaceError);  // names are the shader's, exactly
}

}  // namespace
}  // namespace interface_check_test
}  // namespace avsm
