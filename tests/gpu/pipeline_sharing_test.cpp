// Equal pipelines share their Vulkan objects, which the context's pipeline cache keeps
// for later requests (what makes a hot reload rebuild only the edited shaders'
// pipelines, and a second renderer on a context compile nothing the first did).
#include <gtest/gtest.h>

#include "gpu/pipeline.h"
#include "support/gpu_test.h"

namespace avsm::testing {
namespace pipeline_sharing_test {  // one per file: test targets are unity builds
namespace {

using PipelineSharingTest = GpuTest;

TEST_F(PipelineSharingTest, EqualRequestsShareAndDifferentOnesDoNot) {
  // Names of this test's own: earlier tests in the process leave their pipelines cached.
  const std::vector<uint32_t> fill = shaders().load("shaders/tests/fill.comp");
  const uint64_t before = gpu::Pipeline::created_count();
  gpu::Pipeline first = gpu::Pipeline::compute(ctx(), fill, "fill (sharing)");
  gpu::Pipeline second = gpu::Pipeline::compute(ctx(), fill, "fill (sharing)");
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 1);
  EXPECT_EQ(first.handle(), second.handle());
  EXPECT_EQ(first.layout(), second.layout());
  EXPECT_EQ(second.local_size(), first.local_size());
  EXPECT_EQ(second.bindings().size(), first.bindings().size());

  // Another name (debug labels differ) or other code: a pipeline of its own.
  gpu::Pipeline renamed = gpu::Pipeline::compute(ctx(), fill, "fill (sharing) again");
  EXPECT_NE(renamed.handle(), first.handle());
  std::vector<uint32_t> other_code = shaders().load("shaders/tests/graph_fill.comp");
  gpu::Pipeline other = gpu::Pipeline::compute(ctx(), other_code, "fill (sharing)");
  EXPECT_NE(other.handle(), first.handle());
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 3);
}

TEST_F(PipelineSharingTest, SharedObjectsLiveUntilTheLastUserGoes) {
  const std::vector<uint32_t> fill = shaders().load("shaders/tests/fill.comp");
  gpu::Pipeline kept;
  {
    gpu::Pipeline first = gpu::Pipeline::compute(ctx(), fill, "fill (lifetime)");
    kept = gpu::Pipeline::compute(ctx(), fill, "fill (lifetime)");
  }
  // `first` is gone; `kept` still works (validation would flag a destroyed pipeline),
  // even once the cache may drop every unused pipeline.
  ctx().pipelines().set_unused_limit(0);
  ctx().submit_and_wait([&](VkCommandBuffer cmd) { kept.bind(cmd); });
  ctx().pipelines().set_unused_limit(gpu::PipelineCache::kDefaultUnusedLimit);
}

// A later renderer finds the pipelines an earlier one compiled, though nothing used them
// between; each pipeline compiled destroys the unused ones beyond the limit, those asked
// for longest ago first (what bounds the memory of the pipelines hot reload replaced).
TEST_F(PipelineSharingTest, UnusedPipelinesAreKeptUpToTheLimitOldestGoFirst) {
  const std::vector<uint32_t> fill = shaders().load("shaders/tests/fill.comp");
  gpu::PipelineCache& cache = ctx().pipelines();
  cache.set_unused_limit(0);  // none left over from earlier tests
  cache.set_unused_limit(2);
  const uint64_t before = gpu::Pipeline::created_count();
  auto compile_and_drop = [&](const std::string& name) { gpu::Pipeline::compute(ctx(), fill, name); };
  compile_and_drop("fill (a)");
  compile_and_drop("fill (a)");  // kept while unused: not compiled again
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 1);
  EXPECT_EQ(cache.unused_count(), 1u);

  gpu::Pipeline in_use = gpu::Pipeline::compute(ctx(), fill, "fill (in use)");
  compile_and_drop("fill (b)");
  compile_and_drop("fill (c)");
  EXPECT_EQ(cache.unused_count(), 3u);  // the limit applies when the next one is compiled
  compile_and_drop("fill (d)");         // (a), asked for longest ago, goes
  EXPECT_EQ(cache.unused_count(), 3u);
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 5);
  compile_and_drop("fill (b)");
  compile_and_drop("fill (c)");
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 5);
  compile_and_drop("fill (a)");  // compiled again; (d) is now the oldest and goes
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 6);
  compile_and_drop("fill (b)");
  compile_and_drop("fill (c)");
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 6);
  compile_and_drop("fill (d)");
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 7);

  // One in use is never dropped, however low the limit.
  cache.set_unused_limit(0);
  EXPECT_EQ(cache.unused_count(), 0u);
  ctx().submit_and_wait([&](VkCommandBuffer cmd) { in_use.bind(cmd); });
  EXPECT_EQ(gpu::Pipeline::compute(ctx(), fill, "fill (in use)").handle(), in_use.handle());
  EXPECT_EQ(gpu::Pipeline::created_count(), before + 7);
  cache.set_unused_limit(gpu::PipelineCache::kDefaultUnusedLimit);
}

}  // namespace
}  // namespace pipeline_sharing_test
}  // namespace avsm::testing
