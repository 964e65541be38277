// The lookup in the host's own descriptor sets, without a device: shadow_lookup.glsl
// compiled with the host's set and binding macros declares exactly the entries
// avsm::shadow_lookup_layout() gives for those numbers, and ShadowLookupBuffers::writes()
// writes each buffer at its binding.
#include <gtest/gtest.h>

#include <stdexcept>
#include <string>
#include <vector>

#include "avsm/shadows.h"
#include "gpu/shader_compiler.h"
#include "gpu/spirv_reflect.h"

namespace avsm {
namespace shadow_lookup_layout_test {  // one per file: test targets are unity builds
namespace {

// A compute shader that looks light 0 up, with `defines` before the include.
std::vector<gpu::DescriptorBinding> lookup_bindings(const std::string& defines) {
  const std::string source = "#version 460\n#extension GL_GOOGLE_include_directive : require\n" + defines +
                             "#include \"common/shadow_lookup.glsl\"\n"
                             "layout(local_size_x = 1) in;\n"
                             "layout(set = 0, binding = 0) buffer Out { float result; };\n"
                             "void main() { result = light_transmittance(0u, vec3(0.0)); }\n";
  const ShaderLocation package = ShaderLocation::of_package();
  gpu::ShaderCompileOptions options;
  options.include_dirs = gpu::glsl_include_dirs({package.glsl_root, package.spirv_root});
  const gpu::CompiledShader shader = gpu::compile_glsl(source, "lookup_test.comp", gpu::ShaderStage::Compute, options);
  std::vector<gpu::DescriptorBinding> lookup;
  for (const gpu::DescriptorBinding& b : gpu::reflect_spirv(shader.spirv).bindings)
    if (b.name != "Out") lookup.push_back(b);
  return lookup;
}

// The reflected binding of the block `name`.
const gpu::DescriptorBinding& named(const std::vector<gpu::DescriptorBinding>& bindings, const std::string& name) {
  for (const gpu::DescriptorBinding& b : bindings)
    if (b.name == name) return b;
  throw std::runtime_error("no binding " + name);
}

// The shader's blocks (four, and the page requests where it asks for pages) are where
// `expected` says, in `set`, and nothing else is.
void expect_layout(const std::vector<gpu::DescriptorBinding>& reflected, uint32_t set,
                   const ShadowLookupBindings& expected, bool asks_for_pages) {
  ASSERT_EQ(reflected.size(), asks_for_pages ? 5u : 4u);
  const auto layout = shadow_lookup_layout(expected, VK_SHADER_STAGE_COMPUTE_BIT);
  const char* blocks[5] = {"ShadowParameters", "ShadowMapAtlas", "ShadowListHeads", "ShadowListNodes",
                           "ShadowPageRequests"};
  for (int i = 0; i < (asks_for_pages ? 5 : 4); ++i) {
    const gpu::DescriptorBinding& b = named(reflected, blocks[i]);
    EXPECT_EQ(b.set, set) << blocks[i];
    EXPECT_EQ(b.binding, layout[i].binding) << blocks[i];
    EXPECT_EQ(b.type, layout[i].descriptorType) << blocks[i];
    EXPECT_EQ(b.count, layout[i].descriptorCount) << blocks[i];
    EXPECT_EQ(layout[i].stageFlags, VkShaderStageFlags(VK_SHADER_STAGE_COMPUTE_BIT));
    EXPECT_EQ(layout[i].pImmutableSamplers, nullptr);
  }
}

TEST(ShadowLookupLayout, HostChosenSetAndBindingsMatchTheLayout) {
  const std::vector<gpu::DescriptorBinding> reflected = lookup_bindings(
      "#define AVSM_SHADOW_SET 2\n#define AVSM_SHADOW_PARAMETERS_BINDING 7\n#define AVSM_SHADOW_ATLAS_BINDING 2\n"
      "#define AVSM_SHADOW_LIST_HEADS_BINDING 9\n#define AVSM_SHADOW_LIST_NODES_BINDING 4\n"
      "#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 5\n");
  expect_layout(reflected, 2, {7, 2, 9, 4, 5}, /*asks_for_pages=*/true);
}

TEST(ShadowLookupLayout, OneBindingMeansFourConsecutiveInSetZero) {
  // The layout's fifth entry (the page requests, at 8) is one this shader leaves unused.
  expect_layout(lookup_bindings("#define AVSM_SHADOW_BINDING 4\n"), 0, ShadowLookupBindings::consecutive(4),
                /*asks_for_pages=*/false);
  EXPECT_EQ(ShadowLookupBindings::consecutive(4).page_requests, 8u);
}

TEST(ShadowLookupLayout, MissingBindingsAreACompileErrorThatSaysWhatToDefine) {
  try {
    lookup_bindings("#define AVSM_SHADOW_PARAMETERS_BINDING 1\n");
    FAIL() << "compiled without the atlas and list bindings";
  } catch (const gpu::ShaderCompileError& e) {
    EXPECT_NE(std::string(e.what()).find("define AVSM_SHADOW_BINDING or all four"), std::string::npos) << e.what();
  }
}

TEST(ShadowLookupLayout, RejectsSharedNumbersAndNoStages) {
  try {
    shadow_lookup_layout({1, 2, 1, 3}, VK_SHADER_STAGE_COMPUTE_BIT);
    FAIL() << "accepted two buffers at binding 1";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("avsm::shadow_lookup_layout: bindings 1, 2, 1, 3"), std::string::npos)
        << e.what();
  }
  EXPECT_THROW(shadow_lookup_layout({0, 1, 2, 3, 3}, VK_SHADER_STAGE_COMPUTE_BIT), std::invalid_argument);
  try {
    shadow_lookup_layout({}, 0);
    FAIL() << "accepted no stages";
  } catch (const std::invalid_argument& e) {
    EXPECT_NE(std::string(e.what()).find("stages is 0"), std::string::npos) << e.what();
  }
}

TEST(ShadowLookupLayout, WritesPutEachBufferAtItsBinding) {
  ShadowLookupBuffers buffers;
  buffers.parameters.buffer = (VkBuffer)uintptr_t(0x10);  // handles are only copied
  buffers.atlas.buffer = (VkBuffer)uintptr_t(0x20);
  buffers.list_heads.buffer = (VkBuffer)uintptr_t(0x30);
  buffers.list_nodes.buffer = (VkBuffer)uintptr_t(0x40);
  buffers.page_requests.buffer = (VkBuffer)uintptr_t(0x50);
  const VkDescriptorSet set = (VkDescriptorSet)uintptr_t(0x99);
  const auto writes = buffers.writes(set, {3, 0, 5, 1, 2});
  const uint32_t bindings[5] = {3, 0, 5, 1, 2};
  const VkDescriptorBufferInfo* infos[5] = {&buffers.parameters, &buffers.atlas, &buffers.list_heads,
                                            &buffers.list_nodes, &buffers.page_requests};
  for (int i = 0; i < 5; ++i) {
    EXPECT_EQ(writes[i].sType, VK_STRUCTURE_TYPE_WRITE_DESCRIPTOR_SET);
    EXPECT_EQ(writes[i].dstSet, set);
    EXPECT_EQ(writes[i].dstBinding, bindings[i]);
    EXPECT_EQ(writes[i].descriptorCount, 1u);
    EXPECT_EQ(writes[i].descriptorType, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER);
    EXPECT_EQ(writes[i].pBufferInfo, infos[i]);
  }
}

// The atlas and the lists are regions of larger buffers: the writes take each range's
// offset and size, and fall back to the whole unused buffer where a range is absent.
TEST(ShadowLookupLayout, BuffersKeepEachRangesOffsetAndSize) {
  ShadowLookupResources lookup;
  lookup.parameters = {(VkBuffer)uintptr_t(0x10), 0, VK_WHOLE_SIZE};
  lookup.atlas = {(VkBuffer)uintptr_t(0x20), 256, 4096};
  lookup.list_heads = {(VkBuffer)uintptr_t(0x30), 64, 1024};
  lookup.unused_buffer = (VkBuffer)uintptr_t(0x50);  // list_nodes: absent
  const ShadowLookupBuffers buffers = lookup_buffers(lookup);
  const auto expect = [](const VkDescriptorBufferInfo& info, uintptr_t buffer, VkDeviceSize offset, VkDeviceSize range) {
    EXPECT_EQ(info.buffer, (VkBuffer)buffer);
    EXPECT_EQ(info.offset, offset);
    EXPECT_EQ(info.range, range);
  };
  expect(buffers.parameters, 0x10, 0, VK_WHOLE_SIZE);
  expect(buffers.atlas, 0x20, 256, 4096);
  expect(buffers.list_heads, 0x30, 64, 1024);
  expect(buffers.list_nodes, 0x50, 0, VK_WHOLE_SIZE);
}

}  // namespace
}  // namespace shadow_lookup_layout_test
}  // namespace avsm
