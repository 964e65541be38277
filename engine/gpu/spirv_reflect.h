#pragma once
// SPIR-V reflection (through SPIRV-Cross) for pipeline layouts and interface checks:
// descriptor bindings with their names, the push-constant block, the layout of every
// struct in push-constant and buffer blocks, the stage and the compute local size.
// Reading the layout from the shader keeps C++ and GLSL from drifting apart and
// lets a hot-reloaded shader change its bindings.
#include <vulkan/vulkan.h>

#include <array>
#include <cstdint>
#include <optional>
#include <span>
#include <string>
#include <vector>

namespace avsm::gpu {

struct ReflectedMember {
  std::string name;
  uint32_t offset = 0;
  uint32_t size = 0;  // bytes; a whole array for array members (0 for a runtime array)
};

// A struct as the shader lays it out (std430 / push-constant rules).
struct ReflectedStruct {
  std::string name;   // the GLSL type name
  uint32_t size = 0;  // its array stride when it is an array element, else its declared size
  std::vector<ReflectedMember> members;
};

struct DescriptorBinding {
  uint32_t set = 0;
  uint32_t binding = 0;
  VkDescriptorType type = VK_DESCRIPTOR_TYPE_MAX_ENUM;
  uint32_t count = 1;
  std::string name;  // buffers: the block name; images and samplers: the variable name
  // Buffers: bytes before a trailing runtime array (the whole block if it has none),
  // and that array's stride (0: no runtime array).
  uint32_t fixed_bytes = 0;
  uint32_t runtime_stride = 0;
};

struct ShaderReflection {
  VkShaderStageFlagBits stage = VK_SHADER_STAGE_COMPUTE_BIT;
  std::string entry_point = "main";
  std::string source_file;                  // from debug info, else empty
  std::vector<DescriptorBinding> bindings;  // sorted by (set, binding)
  std::optional<ReflectedStruct> push_constants;
  std::vector<ReflectedStruct> structs;  // every named struct in push-constant and buffer blocks
  std::array<uint32_t, 3> local_size = {1, 1, 1};
};

// Throws std::runtime_error on malformed SPIR-V.
ShaderReflection reflect_spirv(std::span<const uint32_t> words);

}  // namespace avsm::gpu
