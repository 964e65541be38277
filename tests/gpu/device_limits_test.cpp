// The device's limits, checked before anything is made (gpu/device_limits.h): a resource
// over one is a ResourceLimitError that names it, what it needs, the limit and the
// setting that sizes it, and Vulkan is never asked for it (the fixture fails the test
// on any validation message).
#include <gmock/gmock.h>
#include <gtest/gtest.h>

#include <rendergraph/rendergraph.h>
#include <rendergraph/vulkan/executor.h>

#include <algorithm>
#include <functional>
#include <string>

#include "gpu/device_limits.h"
#include "gpu/resources.h"
#include "support/gpu_test.h"

namespace avsm {
namespace device_limits_test {  // one per file: test targets are unity builds
namespace {

using ::testing::HasSubstr;
using testing::GpuTest;

// The ResourceLimitError `make` throws; fails the test when it throws none.
std::string limit_error(const std::function<void()>& make) {
  try {
    make();
  } catch (const gpu::ResourceLimitError& e) {
    return e.what();
  }
  ADD_FAILURE() << "no ResourceLimitError";
  return {};
}

TEST_F(GpuTest, StorageBufferOverTheBindingRangeIsRefusedByName) {
  const VkDeviceSize range = ctx().info().max_storage_buffer_range;
  const gpu::BufferDesc desc{range + 256, VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, gpu::MemoryLocation::DeviceLocal,
                             "test map", "the test's resolution"};
  const std::string message = limit_error([&] { gpu::Buffer::create(ctx(), desc); });
  EXPECT_THAT(message, HasSubstr("'test map' needs " + gpu::format_mib(range + 256)));
  EXPECT_THAT(message, HasSubstr("over the device's maxStorageBufferRange of " + gpu::format_mib(range)));
  EXPECT_THAT(message, HasSubstr("; lower the test's resolution"));
  // The frame graph's planning query refuses it the same way.
  EXPECT_EQ(limit_error([&] { gpu::memory_requirements(ctx(), desc); }), message);

  // Only a shader binding has the range: the same bytes to copy through are fine.
  gpu::BufferDesc transfer = desc;
  transfer.usage = VK_BUFFER_USAGE_TRANSFER_DST_BIT;
  EXPECT_EQ(gpu::Buffer::create(ctx(), transfer).size(), range + 256);
}

TEST_F(GpuTest, ImagesOverTheDimensionLimitsAreRefusedByName) {
  gpu::ImageDesc wide;
  wide.width = ctx().info().max_image_dimension_2d + 1;
  wide.format = VK_FORMAT_R32_UINT;
  wide.usage = VK_IMAGE_USAGE_STORAGE_BIT;
  wide.name = "test heads";
  wide.sized_by = "the test's resolution";
  const std::string message = limit_error([&] { gpu::Image::create(ctx(), wide); });
  EXPECT_EQ(message, "'test heads' needs a " + std::to_string(wide.width) +
                         "x1 image, over the device's maxImageDimension2D of " +
                         std::to_string(ctx().info().max_image_dimension_2d) + " texels; lower the test's resolution");
  EXPECT_EQ(limit_error([&] { gpu::memory_requirements(ctx(), wide); }), message);

  gpu::ImageDesc deep;
  deep.depth = ctx().info().max_image_dimension_3d + 1;
  deep.format = VK_FORMAT_R16_SFLOAT;
  deep.usage = VK_IMAGE_USAGE_SAMPLED_BIT;
  deep.name = "test volume";
  EXPECT_THAT(limit_error([&] { gpu::Image::create(ctx(), deep); }),
              HasSubstr("'test volume' needs a 1x1x" + std::to_string(deep.depth) +
                        " image, over the device's maxImageDimension3D"));
}

// A transient of the frame graph is refused while the plan is made, by its name and the
// setting its declaration gives, before any heap or image exists.
TEST_F(GpuTest, FrameGraphTransientOverTheLimitIsRefusedWhilePlanning) {
  const uint32_t too_wide = ctx().info().max_image_dimension_2d * 2;
  rg::Graph graph;
  graph.add_pass("light 0 clear lists", rg::QueueType::Compute, [&](rg::PassBuilder& b) {
    const rg::TextureDesc heads{too_wide, too_wide, 1, 1, 1, VK_FORMAT_R32_UINT, "the light's shadow.resolution"};
    b.write(b.create_texture("light 0 list heads", heads), rg::Usage::TransferDst);
    b.side_effect();
  }, [](rg::PassContext&) {});
  const rg::vulkan::DeviceMemoryModel model(ctx());
  EXPECT_THAT(limit_error([&] { graph.compile(model); }),
              HasSubstr("'light 0 list heads' needs a " + std::to_string(too_wide) + "x" + std::to_string(too_wide) +
                        " image, over the device's maxImageDimension2D of " +
                        std::to_string(ctx().info().max_image_dimension_2d) +
                        " texels; lower the light's shadow.resolution"));
}

// Transients that each fit but are alive together: their heap is over the allocation
// limit. The error names the heap and its largest residents with what sizes them, and
// the executor does not keep the plan it could not realise (the next frame fails alike).
TEST_F(GpuTest, FrameGraphHeapOverTheLimitNamesWhatItHolds) {
  const gpu::DeviceInfo& info = ctx().info();
  const uint64_t each = std::min(info.max_memory_allocation_size, info.max_buffer_size) / 4 * 3;
  rg::Graph graph;
  struct Data {
    rg::BufferHandle a, b;
  };
  const Data& written = graph.add_pass<Data>("write", rg::QueueType::Transfer, [&](rg::PassBuilder& b, Data& d) {
    d.a = b.write(b.create_buffer("big a", {each, "setting a"}), rg::Usage::TransferDst);
    d.b = b.write(b.create_buffer("big b", {each, "setting b"}), rg::Usage::TransferDst);
  }, [](const Data&, rg::PassContext&) {});
  graph.add_pass("read", rg::QueueType::Transfer, [&](rg::PassBuilder& b) {
    b.read(written.a, rg::Usage::TransferSrc);
    b.read(written.b, rg::Usage::TransferSrc);
    b.side_effect();
  }, [](rg::PassContext&) {});

  rg::vulkan::Executor executor(ctx(), gpu::TimestampMode::Exact);
  VkCommandBuffer cmd = ctx().allocate_command_buffer("heap over the limit");
  VkCommandBufferBeginInfo begin{VK_STRUCTURE_TYPE_COMMAND_BUFFER_BEGIN_INFO};
  vkBeginCommandBuffer(cmd, &begin);
  for (int frame = 0; frame < 2; ++frame) {
    const std::string message = limit_error([&] { executor.record(graph, cmd); });
    EXPECT_THAT(message, HasSubstr("'frame graph heap 0' needs " + gpu::format_mib(2 * each) + ", over the device's "));
    EXPECT_THAT(message, HasSubstr("; lower what it holds, largest first: 'big a' " + gpu::format_mib(each) +
                                   " (setting a), 'big b' " + gpu::format_mib(each) + " (setting b)"));
  }
  vkEndCommandBuffer(cmd);
  vkFreeCommandBuffers(ctx().device(), ctx().command_pool(), 1, &cmd);
}

TEST_F(GpuTest, MemoryOverTheHeapOrAllocationLimitIsRefusedByName) {
  const gpu::DeviceInfo& info = ctx().info();
  const VkPhysicalDeviceMemoryProperties& memory = ctx().memory_properties();
  const uint32_t type = uint32_t(ctx().find_memory_type(~0u, VK_MEMORY_PROPERTY_DEVICE_LOCAL_BIT));
  const VkDeviceSize heap = memory.memoryHeaps[memory.memoryTypes[type].heapIndex].size;
  const VkDeviceSize bytes = std::max(heap, info.max_memory_allocation_size) + (1 << 20);
  const std::string message = limit_error([&] {
    gpu::MemoryHeap(ctx(), bytes, 1u << type, gpu::MemoryLocation::DeviceLocal, "test heap",
                    "what the test puts in it");
  });
  EXPECT_THAT(message, HasSubstr("'test heap' needs " + gpu::format_mib(bytes) + ", over the device's "));
  EXPECT_THAT(message, HasSubstr("; lower what the test puts in it"));
  const std::string allocation_limit = "maxMemoryAllocationSize of " + gpu::format_mib(info.max_memory_allocation_size);
  EXPECT_THAT(message, ::testing::AnyOf(HasSubstr(allocation_limit), HasSubstr("memory heap")));
}

}  // namespace
}  // namespace device_limits_test
}  // namespace avsm
