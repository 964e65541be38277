#pragma once
// Test harness for GPU tests: one Vulkan context with validation and
// synchronization validation on, shared by all tests of the executable. After
// every test, any validation message fails that test (see TearDown).
#include <gtest/gtest.h>

#include "gpu/context.h"
#include "gpu/shader_compiler.h"
#include "tests/fill.h"

namespace avsm::testing {

// Push constants of shaders/tests/fill.comp: values[i] = i * scale + offset.
using shared::FillPush;

gpu::Context& test_context();
const gpu::ShaderLibrary& test_shaders();

class GpuTest : public ::testing::Test {
 protected:
  void SetUp() override;
  void TearDown() override;
  gpu::Context& ctx() { return test_context(); }
  const gpu::ShaderLibrary& shaders() { return test_shaders(); }
  // For tests that provoke messages on purpose: returns them and clears the log,
  // so TearDown sees only what was not expected.
  std::vector<gpu::ValidationMessage> take_validation_messages();
};

}  // namespace avsm::testing
