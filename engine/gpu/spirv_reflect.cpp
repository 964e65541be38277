#include "gpu/spirv_reflect.h"

#include <algorithm>
#include <map>
#include <stdexcept>

namespace avsm::gpu {
namespace {

// Opcodes, decorations and enums from the SPIR-V specification.
enum Op : uint32_t {
  OpName = 5,
  OpEntryPoint = 15,
  OpExecutionMode = 16,
  OpTypeImage = 25,
  OpTypeSampler = 26,
  OpTypeSampledImage = 27,
  OpTypeArray = 28,
  OpTypeRuntimeArray = 29,
  OpTypeStruct = 30,
  OpTypePointer = 32,
  OpConstant = 43,
  OpVariable = 59,
  OpDecorate = 71,
  OpExecutionModeId = 331,
};
constexpr uint32_t kDecorationBlock = 2, kDecorationBufferBlock = 3, kDecorationBinding = 33,
                   kDecorationDescriptorSet = 34;
constexpr uint32_t kStorageUniformConstant = 0, kStorageUniform = 2, kStoragePushConstant = 9,
                   kStorageStorageBuffer = 12;
constexpr uint32_t kExecutionModeLocalSize = 17, kExecutionModeLocalSizeId = 38;
constexpr uint32_t kDimBuffer = 5, kDimSubpassData = 6;

struct TypeInfo {
  uint32_t opcode = 0;
  std::vector<uint32_t> operands;  // words after the result id
};

VkShaderStageFlagBits stage_of_model(uint32_t model) {
  switch (model) {
    case 0: return VK_SHADER_STAGE_VERTEX_BIT;
    case 3: return VK_SHADER_STAGE_GEOMETRY_BIT;
    case 4: return VK_SHADER_STAGE_FRAGMENT_BIT;
    case 5: return VK_SHADER_STAGE_COMPUTE_BIT;
    default: throw std::runtime_error("SPIR-V: unsupported execution model " + std::to_string(model));
  }
}

std::string read_string(std::span<const uint32_t> words) {
  std::string s;
  for (uint32_t w : words)
    for (int i = 0; i < 4; ++i) {
      char c = char((w >> (8 * i)) & 0xff);
      if (c == 0) return s;
      s.push_back(c);
    }
  return s;
}

}  // namespace

ShaderReflection reflect_spirv(std::span<const uint32_t> words) {
  if (words.size() < 5 || words[0] != 0x07230203u) throw std::runtime_error("SPIR-V: bad header");
  ShaderReflection out;
  std::map<uint32_t, TypeInfo> types;
  std::map<uint32_t, uint32_t> constants;
  std::map<uint32_t, std::string> names;
  std::map<uint32_t, uint32_t> set_of, binding_of;
  std::map<uint32_t, uint32_t> block_kind;  // struct id -> Block / BufferBlock
  std::vector<std::pair<uint32_t, std::pair<uint32_t, uint32_t>>> variables;  // id -> (pointer type, storage)
  std::array<uint32_t, 3> local_size_ids = {0, 0, 0};

  for (size_t at = 5; at < words.size();) {
    uint32_t count = words[at] >> 16, opcode = words[at] & 0xffff;
    if (count == 0 || at + count > words.size()) throw std::runtime_error("SPIR-V: truncated instruction");
    std::span<const uint32_t> ops = words.subspan(at + 1, count - 1);
    switch (opcode) {
      case OpName: names[ops[0]] = read_string(ops.subspan(1)); break;
      case OpEntryPoint:
        out.stage = stage_of_model(ops[0]);
        out.entry_point = read_string(ops.subspan(2));
        break;
      case OpExecutionMode:
        if (ops[1] == kExecutionModeLocalSize) out.local_size = {ops[2], ops[3], ops[4]};
        break;
      case OpExecutionModeId:  // SPIR-V 1.6 spells the local size with constant ids
        if (ops[1] == kExecutionModeLocalSizeId) local_size_ids = {ops[2], ops[3], ops[4]};
        break;
      case OpDecorate:
        if (ops[1] == kDecorationBinding) binding_of[ops[0]] = ops[2];
        if (ops[1] == kDecorationDescriptorSet) set_of[ops[0]] = ops[2];
        if (ops[1] == kDecorationBlock || ops[1] == kDecorationBufferBlock) block_kind[ops[0]] = ops[1];
        break;
      case OpConstant:
        if (ops.size() >= 3) constants[ops[1]] = ops[2];
        break;
      case OpTypeImage:
      case OpTypeSampler:
      case OpTypeSampledImage:
      case OpTypeArray:
      case OpTypeRuntimeArray:
      case OpTypeStruct:
        types[ops[0]] = {opcode, {ops.begin() + 1, ops.end()}};
        break;
      case OpTypePointer: types[ops[0]] = {opcode, {ops[1], ops[2]}}; break;  // storage class, pointee
      case OpVariable: variables.push_back({ops[1], {ops[0], ops[2]}}); break;
      default: break;
    }
    at += count;
  }

  if (local_size_ids[0] != 0)
    for (int axis = 0; axis < 3; ++axis) out.local_size[axis] = constants.at(local_size_ids[axis]);

  for (const auto& [id, typed] : variables) {
    auto [pointer_type, storage] = typed;
    if (storage == kStoragePushConstant) {
      out.uses_push_constants = true;
      continue;
    }
    if (storage != kStorageUniformConstant && storage != kStorageUniform && storage != kStorageStorageBuffer)
      continue;
    if (!binding_of.count(id)) continue;
    DescriptorBinding b;
    b.set = set_of.count(id) ? set_of[id] : 0;
    b.binding = binding_of[id];
    b.name = names.count(id) ? names[id] : "";
    uint32_t type = types[pointer_type].operands.at(1);
    // Unwrap arrays: the binding's count.
    while (types[type].opcode == OpTypeArray || types[type].opcode == OpTypeRuntimeArray) {
      if (types[type].opcode == OpTypeArray) b.count *= constants[types[type].operands.at(1)];
      type = types[type].operands.at(0);
    }
    const TypeInfo& t = types[type];
    if (storage == kStorageStorageBuffer) {
      b.type = VK_DESCRIPTOR_TYPE_STORAGE_BUFFER;
    } else if (storage == kStorageUniform) {
      b.type = block_kind[type] == kDecorationBufferBlock ? VK_DESCRIPTOR_TYPE_STORAGE_BUFFER
                                                          : VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER;
    } else if (t.opcode == OpTypeSampler) {
      b.type = VK_DESCRIPTOR_TYPE_SAMPLER;
    } else if (t.opcode == OpTypeSampledImage) {
      b.type = VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER;
    } else if (t.opcode == OpTypeImage) {
      // operands: sampled type, dim, depth, arrayed, ms, sampled, format
      uint32_t dim = t.operands.at(1), sampled = t.operands.at(5);
      if (dim == kDimSubpassData) b.type = VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT;
      else if (dim == kDimBuffer) b.type = sampled == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER : VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER;
      else b.type = sampled == 2 ? VK_DESCRIPTOR_TYPE_STORAGE_IMAGE : VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE;
    } else {
      throw std::runtime_error("SPIR-V: unsupported descriptor type for binding " + std::to_string(b.binding));
    }
    out.bindings.push_back(b);
  }
  std::sort(out.bindings.begin(), out.bindings.end(), [](const auto& a, const auto& b) {
    return std::pair(a.set, a.binding) < std::pair(b.set, b.binding);
  });
  return out;
}

}  // namespace avsm::gpu
