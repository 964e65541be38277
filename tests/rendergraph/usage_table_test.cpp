// The usage table: shader stages follow the queue, creation flags follow the usages.
#include <gtest/gtest.h>

#include <rendergraph/usage.h>
#include <rendergraph/vk_names.h>

namespace {

using rg::QueueType;
using rg::Usage;

TEST(UsageTable, ShaderStagesDependOnTheQueue) {
  EXPECT_EQ(rg::usage_info(Usage::Sampled, QueueType::Graphics).stages,
            VK_PIPELINE_STAGE_2_PRE_RASTERIZATION_SHADERS_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT);
  EXPECT_EQ(rg::usage_info(Usage::Sampled, QueueType::Compute).stages,
            VkPipelineStageFlags2{VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT});
  EXPECT_EQ(rg::usage_info(Usage::TransferDst, QueueType::Compute).stages,
            VkPipelineStageFlags2{VK_PIPELINE_STAGE_2_TRANSFER_BIT});
}

TEST(UsageTable, EveryUsageHasANameAndAConsistentWriteBit) {
  for (uint32_t i = 0; i < rg::kUsageCount; ++i) {
    const auto usage = static_cast<Usage>(i);
    EXPECT_STRNE(rg::to_string(usage), "?");
    const rg::UsageInfo info = rg::usage_info(usage, QueueType::Graphics);
    EXPECT_EQ(info.is_write, rg::write_access_bits(info.access) != 0) << rg::to_string(usage);
  }
}

TEST(UsageTable, CreationFlagsAreTheUnionOverUsages) {
  EXPECT_EQ(rg::image_usage_flags({Usage::Sampled, Usage::ColorAttachment, Usage::TransferSrc}),
            VK_IMAGE_USAGE_SAMPLED_BIT | VK_IMAGE_USAGE_COLOR_ATTACHMENT_BIT | VK_IMAGE_USAGE_TRANSFER_SRC_BIT);
  EXPECT_EQ(rg::image_usage_flags({Usage::StorageRead, Usage::StorageReadWrite}),
            VkImageUsageFlags{VK_IMAGE_USAGE_STORAGE_BIT});
  EXPECT_EQ(rg::buffer_usage_flags({Usage::StorageWrite, Usage::IndirectRead, Usage::UniformRead}),
            VK_BUFFER_USAGE_STORAGE_BUFFER_BIT | VK_BUFFER_USAGE_INDIRECT_BUFFER_BIT | VK_BUFFER_USAGE_UNIFORM_BUFFER_BIT);
  EXPECT_EQ(rg::buffer_usage_flags({Usage::VertexRead, Usage::IndexRead, Usage::TransferDst}),
            VK_BUFFER_USAGE_VERTEX_BUFFER_BIT | VK_BUFFER_USAGE_INDEX_BUFFER_BIT | VK_BUFFER_USAGE_TRANSFER_DST_BIT);
}

TEST(UsageTable, UsageProblems) {
  EXPECT_EQ(rg::usage_problem(Usage::Sampled, QueueType::Compute, rg::ResourceKind::Texture), nullptr);
  EXPECT_NE(rg::usage_problem(Usage::Sampled, QueueType::Transfer, rg::ResourceKind::Texture), nullptr);
  EXPECT_NE(rg::usage_problem(Usage::VertexRead, QueueType::Compute, rg::ResourceKind::Buffer), nullptr);
  EXPECT_NE(rg::usage_problem(Usage::DepthAttachmentRead, QueueType::Graphics, rg::ResourceKind::Buffer), nullptr);
  EXPECT_NE(rg::usage_problem(Usage::HostRead, QueueType::Graphics, rg::ResourceKind::Buffer), nullptr);
  EXPECT_EQ(rg::usage_problem(Usage::TransferSrc, QueueType::Transfer, rg::ResourceKind::Buffer), nullptr);
}

TEST(UsageTable, AspectsAndImportStates) {
  EXPECT_EQ(rg::aspect_flags(VK_FORMAT_D32_SFLOAT), VkImageAspectFlags{VK_IMAGE_ASPECT_DEPTH_BIT});
  EXPECT_EQ(rg::aspect_flags(VK_FORMAT_D24_UNORM_S8_UINT), VK_IMAGE_ASPECT_DEPTH_BIT | VK_IMAGE_ASPECT_STENCIL_BIT);
  EXPECT_EQ(rg::aspect_flags(VK_FORMAT_R16G16B16A16_SFLOAT), VkImageAspectFlags{VK_IMAGE_ASPECT_COLOR_BIT});
  const rg::ImportState present = rg::ImportState::of(Usage::Present);
  EXPECT_EQ(present.layout, VK_IMAGE_LAYOUT_PRESENT_SRC_KHR);
  EXPECT_EQ(present.stages, VkPipelineStageFlags2{VK_PIPELINE_STAGE_2_NONE});
}

TEST(VkNames, FlagsAndLayoutsPrintSymbolically) {
  EXPECT_EQ(rg::stage_names(VK_PIPELINE_STAGE_2_COMPUTE_SHADER_BIT | VK_PIPELINE_STAGE_2_FRAGMENT_SHADER_BIT),
            "FRAGMENT_SHADER|COMPUTE_SHADER");
  EXPECT_EQ(rg::access_names(VK_ACCESS_2_SHADER_STORAGE_WRITE_BIT), "SHADER_STORAGE_WRITE");
  EXPECT_EQ(rg::access_names(0), "NONE");
  EXPECT_EQ(rg::layout_name(VK_IMAGE_LAYOUT_GENERAL), "GENERAL");
  EXPECT_EQ(rg::stage_names(VK_PIPELINE_STAGE_2_TASK_SHADER_BIT_EXT), "0x80000");  // unnamed bits stay visible
}

}  // namespace
