#pragma once
// Just enough SPIR-V reflection to build pipeline layouts: descriptor bindings,
// whether push constants are used, the stage and the compute local size.
// Reading the layout from the shader keeps C++ and GLSL from drifting apart and
// lets a hot-reloaded shader change its bindings.
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <span>
#include <string>
#include <vector>

namespace avsm::gpu {

struct DescriptorBinding {
  uint32_t set = 0;
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  uint32_t count = 1;
  std::string name;
};

struct ShaderReflection {
  VkShaderStageFlagBits stage = VK_SHADER_STAGE_COMPUTE_BIT;
  std::string entry_point = "main";
  std::vector<DescriptorBinding> bindings;  // sorted by (set, binding)
  bool uses_push_constants = false;
  std::array<uint32_t, 3> local_size = {1, 1, 1};
};

// Throws std::runtime_error on malformed SPIR-V.
ShaderReflection reflect_spirv(std::span<const uint32_t> words);

}  // namespace avsm::gpu
