// Equal pipelines share their Vulkan objects while one of them is alive (what
// makes a hot reload rebuild only the edited shaders' pipelines).
#include <gtest/gtest.h>

#include "gpu/pipeline.h"
#include "support/gpu_test.h"

namespace avsm::testing {
namespace {

using PipelineSharingTest = GpuTest;

TEST_F(PipelineSharingTest, EqualRequestsShareAndDifferentOnesDoNot) {
  const std::vector<uint32_t> fill = shaders().load("shaders/tests/fill.comp");
  const uint64_t before = gpu::Pipeline::created_count();
  gpu::Pipeline first = gpu::Pipeline::compute(ctx(), fill, "fill");
  gpu::Pipeline second = gpu::Pipeline::compute(ctx(), fill, "fill");
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 1);
  EXPECT_EQ(first.handle(), second.handle());
  EXPECT_EQ(first.layout(), second.layout());
  EXPECT_EQ(second.local_size(), first.local_size());
  EXPECT_EQ(second.bindings().size(), first.bindings().size());

  // Another name (debug labels differ) or other code: a pipeline of its own.
  gpu::Pipeline renamed = gpu::Pipeline::compute(ctx(), fill, "fill again");
  EXPECT_NE(renamed.handle(), first.handle());
  std::vector<uint32_t> other_code = shaders().load("shaders/tests/graph_fill.comp");
  gpu::Pipeline other = gpu::Pipeline::compute(ctx(), other_code, "fill");
  EXPECT_NE(other.handle(), first.handle());
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 3);
}

TEST_F(PipelineSharingTest, SharedObjectsLiveUntilTheLastUserAndAreNotKeptByTheCache) {
  const std::vector<uint32_t> fill = shaders().load("shaders/tests/fill.comp");
  gpu::Pipeline kept;
  {
    gpu::Pipeline first = gpu::Pipeline::compute(ctx(), fill, "fill (lifetime)");
    kept = gpu::Pipeline::compute(ctx(), fill, "fill (lifetime)");
  }
  // `first` is gone; `kept` still works (validation would flag a destroyed pipeline).
  ctx().submit_and_wait([&](VkCommandBuffer cmd) { kept.bind(cmd); });
  kept = gpu::Pipeline();
  // Nobody uses it now: the next request creates it again.
  const uint64_t before = gpu::Pipeline::created_count();
  gpu::Pipeline again = gpu::Pipeline::compute(ctx(), fill, "fill (lifetime)");
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 1);
}

}  // namespace
}  // namespace avsm::testing
