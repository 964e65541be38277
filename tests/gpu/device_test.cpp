#include <gtest/gtest.h>

#include <cstdlib>

#include "gpu/barriers.h"
#include "gpu/resources.h"
#include "gpu/transfer.h"
#include "support/gpu_test.h"

namespace avsm {
namespace device_test {  // one per file: test targets are unity builds
namespace {

using testing::GpuTest;

TEST_F(GpuTest, CreatesDeviceWithQueueAndTimestamps) {
  const gpu::DeviceInfo& info = ctx().info();
  EXPECT_FALSE(info.name.empty());
  EXPECT_GE(info.api_version, VK_API_VERSION_1_3);
  EXPECT_NE(ctx().graphics_queue().handle, VK_NULL_HANDLE);
  EXPECT_GT(info.timestamp_valid_bits, 0u);
  EXPECT_NE(ctx().cmd_push_descriptor_set, nullptr);
  std::printf("device: %s (%s, %s)\n", info.name.c_str(), info.driver_name.c_str(), info.driver_info.c_str());
}

TEST(DeviceSelection, UnknownDeviceNameIsAClearError) {
  gpu::ContextDesc desc;
  desc.device = "no-such-gpu-xyz";
  std::string saved = gpu::env_or_empty("AVSM_DEVICE");
  unsetenv("AVSM_DEVICE");
  try {
    gpu::Context ctx(desc);
    FAIL() << "expected an error";
  } catch (const std::runtime_error& e) {
    EXPECT_NE(std::string(e.what()).find("no-such-gpu-xyz"), std::string::npos) << e.what();
    EXPECT_NE(std::string(e.what()).find("devices:"), std::string::npos) << e.what();
  }
  if (!saved.empty()) setenv("AVSM_DEVICE", saved.c_str(), 1);
}

TEST(DeviceSelection, PicksByIndexOrName) {
  gpu::ContextDesc desc;
  desc.device = "0";
  gpu::Context by_index(desc);
  desc.device = by_index.info().name.substr(0, 4);
  gpu::Context by_name(desc);
  EXPECT_EQ(by_index.info().name, by_name.info().name);
}

// Two buffers placed at the same offset of one heap share memory: what the frame
// graph relies on when it aliases transient resources.
TEST_F(GpuTest, PlacedBuffersAliasTheSameMemory) {
  gpu::BufferDesc a_desc{4096, VK_BUFFER_USAGE_TRANSFER_SRC_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT,
                         gpu::MemoryLocation::DeviceLocal, "alias a"};
  gpu::BufferDesc b_desc = a_desc;
  b_desc.name = "alias b";
  gpu::MemoryRequirements reqs = gpu::memory_requirements(ctx(), a_desc);
  EXPECT_GE(reqs.size, 4096u);
  EXPECT_GT(reqs.alignment, 0u);
  gpu::MemoryHeap heap(ctx(), reqs.size * 2, reqs.memory_type_bits, gpu::MemoryLocation::DeviceLocal, "alias heap");
  gpu::Buffer a = gpu::Buffer::create_placed(ctx(), a_desc, heap, 0);
  gpu::Buffer b = gpu::Buffer::create_placed(ctx(), b_desc, heap, 0);
  std::vector<uint32_t> data(1024);
  for (uint32_t i = 0; i < data.size(); ++i) data[i] = i * 7 + 1;
  gpu::upload_buffer(ctx(), a, data.data(), data.size() * 4);
  EXPECT_EQ(gpu::read_buffer<uint32_t>(ctx(), b), data);

  EXPECT_THROW(gpu::Buffer::create_placed(ctx(), a_desc, heap, reqs.size * 2 - 16), std::runtime_error);
}

TEST_F(GpuTest, PlacedImageUsesTheDriversRequirements) {
  gpu::ImageDesc desc;
  desc.width = desc.height = 64;
  desc.format = VK_FORMAT_R32_SFLOAT;
  desc.usage = VK_IMAGE_USAGE_STORAGE_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT | VK_IMAGE_USAGE_TRANSFER_DST_BIT;
  desc.name = "placed image";
  gpu::MemoryRequirements reqs = gpu::memory_requirements(ctx(), desc);
  EXPECT_GE(reqs.size, 64u * 64u * 4u);
  VkDeviceSize offset = reqs.alignment * 3;
  gpu::MemoryHeap heap(ctx(), offset + reqs.size, reqs.memory_type_bits, gpu::MemoryLocation::DeviceLocal, "image heap");
  gpu::Image image = gpu::Image::create_placed(ctx(), desc, heap, offset);
  std::vector<float> texels(64 * 64);
  for (size_t i = 0; i < texels.size(); ++i) texels[i] = float(i);
  gpu::upload_image(ctx(), image, texels.data(), texels.size() * 4, VK_IMAGE_LAYOUT_GENERAL);
  gpu::ImageRGBA32F back = gpu::read_image(ctx(), image, VK_IMAGE_LAYOUT_GENERAL);
  EXPECT_EQ(back.at(5, 3)[0], float(3 * 64 + 5));
}

}  // namespace
}  // namespace device_test
}  // namespace avsm
