#include "gpu/spirv_reflect.h"

#include <spirv_cross/spirv_cross_c.h>

#include <algorithm>
#include <map>
#include <memory>
#include <stdexcept>

namespace avsm::gpu {
namespace {

// One SPIRV-Cross context per reflection; it owns everything the compiler hands out.
struct CrossContext {
  spvc_context context = nullptr;
  CrossContext() {
    if (spvc_context_create(&context) != SPVC_SUCCESS) throw std::runtime_error("SPIR-V: cannot create a reflector");
  }
  ~CrossContext() { spvc_context_destroy(context); }
  CrossContext(const CrossContext&) = delete;
  CrossContext& operator=(const CrossContext&) = delete;
  [[noreturn]] void fail(const std::string& what) const {
    throw std::runtime_error("SPIR-V: " + what + ": " + spvc_context_get_last_error_string(context));
  }
};

VkShaderStageFlagBits stage_of_model(SpvExecutionModel model) {
  switch (model) {
    case SpvExecutionModelVertex: return VK_SHADER_STAGE_VERTEX_BIT;
    case SpvExecutionModelGeometry: return VK_SHADER_STAGE_GEOMETRY_BIT;
    case SpvExecutionModelFragment: return VK_SHADER_STAGE_FRAGMENT_BIT;
    case SpvExecutionModelGLCompute: return VK_SHADER_STAGE_COMPUTE_BIT;
    default: throw std::runtime_error("SPIR-V: unsupported execution model " + std::to_string(int(model)));
  }
}

// The file named by the module's OpSource, when it carries debug info (-g).
std::string source_file_of(std::span<const uint32_t> words) {
  constexpr uint32_t kOpSource = 3, kOpString = 7;
  std::map<uint32_t, std::string> strings;
  for (size_t at = 5; at < words.size();) {
    uint32_t count = words[at] >> 16, opcode = words[at] & 0xffff;
    if (count == 0 || at + count > words.size()) break;
    if (opcode == kOpString && count >= 3)
      strings[words[at + 1]] = std::string(reinterpret_cast<const char*>(&words[at + 2]), (count - 2) * 4).c_str();
    if (opcode == kOpSource && count >= 4) return strings.count(words[at + 3]) ? strings[words[at + 3]] : "";
    at += count;
  }
  return {};
}

class Reflector {
 public:
  Reflector(const CrossContext& cross, spvc_compiler compiler) : cross_(cross), compiler_(compiler) {}

  // The layout of a block or struct type; `stride`, when non-zero, is its size as an array element.
  ReflectedStruct struct_of(spvc_type_id type_id, uint32_t stride, ShaderReflection& out) const {
    spvc_type type = spvc_compiler_get_type_handle(compiler_, type_id);
    ReflectedStruct s;
    s.name = spvc_compiler_get_name(compiler_, type_id);
    size_t declared = 0;
    if (spvc_compiler_get_declared_struct_size(compiler_, type, &declared) != SPVC_SUCCESS)
      cross_.fail("struct '" + s.name + "' has no size");
    s.size = stride ? stride : uint32_t(declared);
    for (unsigned i = 0; i < spvc_type_get_num_member_types(type); ++i) {
      ReflectedMember m;
      m.name = spvc_compiler_get_member_name(compiler_, type_id, i);
      unsigned offset = 0;
      size_t size = 0;
      spvc_compiler_type_struct_member_offset(compiler_, type, i, &offset);
      spvc_compiler_get_declared_struct_member_size(compiler_, type, i, &size);
      m.offset = offset;
      m.size = uint32_t(size);
      s.members.push_back(m);
      note_nested_struct(type, i, out);
    }
    return s;
  }

  DescriptorBinding binding_of(const spvc_reflected_resource& resource, VkDescriptorType kind, ShaderReflection& out) const {
    DescriptorBinding b;
    b.set = spvc_compiler_get_decoration(compiler_, resource.id, SpvDecorationDescriptorSet);
    b.binding = spvc_compiler_get_decoration(compiler_, resource.id, SpvDecorationBinding);
    b.name = resource.name;
    b.type = kind;
    spvc_type type = spvc_compiler_get_type_handle(compiler_, resource.type_id);
    for (unsigned d = 0; d < spvc_type_get_num_array_dimensions(type); ++d) b.count *= spvc_type_get_array_dimension(type, d);
    if (kind == VK_DESCRIPTOR_TYPE_STORAGE_BUFFER || kind == VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER)
      describe_block(resource.base_type_id, b, out);
    return b;
  }

 private:
  void describe_block(spvc_type_id block_id, DescriptorBinding& b, ShaderReflection& out) const {
    spvc_type block = spvc_compiler_get_type_handle(compiler_, block_id);
    ReflectedStruct layout = struct_of(block_id, 0, out);
    b.fixed_bytes = layout.size;
    unsigned members = spvc_type_get_num_member_types(block);
    if (members == 0) return;
    spvc_type last = spvc_compiler_get_type_handle(compiler_, spvc_type_get_member_type(block, members - 1));
    unsigned dims = spvc_type_get_num_array_dimensions(last);
    if (dims > 0 && spvc_type_get_array_dimension(last, dims - 1) == 0) {
      unsigned stride = 0;
      spvc_compiler_type_struct_member_array_stride(compiler_, block, members - 1, &stride);
      b.runtime_stride = stride;
    }
    remember(std::move(layout), out);
  }

  // Records the struct type of member `i` of `parent`, if it is one.
  void note_nested_struct(spvc_type parent, unsigned i, ShaderReflection& out) const {
    spvc_type_id member_id = spvc_type_get_member_type(parent, i);
    spvc_type member = spvc_compiler_get_type_handle(compiler_, member_id);
    if (spvc_type_get_basetype(member) != SPVC_BASETYPE_STRUCT) return;
    unsigned stride = 0;
    if (spvc_type_get_num_array_dimensions(member) > 0)
      spvc_compiler_type_struct_member_array_stride(compiler_, parent, i, &stride);
    spvc_type_id element_id = spvc_type_get_base_type_id(member);
    std::string name = spvc_compiler_get_name(compiler_, element_id);
    for (const ReflectedStruct& s : out.structs)
      if (s.name == name) return;
    remember(struct_of(element_id, stride, out), out);
  }

  static void remember(ReflectedStruct s, ShaderReflection& out) {
    if (s.name.empty()) return;
    for (const ReflectedStruct& known : out.structs)
      if (known.name == s.name) return;
    out.structs.push_back(std::move(s));
  }

  const CrossContext& cross_;
  spvc_compiler compiler_;
};

struct ResourceKind {
  spvc_resource_type type;
  VkDescriptorType descriptor;
};

// Images of Buffer dimension are texel buffers.
VkDescriptorType image_descriptor(spvc_compiler compiler, const spvc_reflected_resource& r, VkDescriptorType image,
                                  VkDescriptorType texel_buffer) {
  spvc_type type = spvc_compiler_get_type_handle(compiler, r.base_type_id);
  return spvc_type_get_image_dimension(type) == SpvDimBuffer ? texel_buffer : image;
}

}  // namespace

ShaderReflection reflect_spirv(std::span<const uint32_t> words) {
  if (words.size() < 5 || words[0] != 0x07230203u) throw std::runtime_error("SPIR-V: bad header");
  CrossContext cross;
  spvc_parsed_ir ir = nullptr;
  if (spvc_context_parse_spirv(cross.context, words.data(), words.size(), &ir) != SPVC_SUCCESS)
    cross.fail("cannot parse the module");
  spvc_compiler compiler = nullptr;
  if (spvc_context_create_compiler(cross.context, SPVC_BACKEND_NONE, ir, SPVC_CAPTURE_MODE_TAKE_OWNERSHIP,
                                   &compiler) != SPVC_SUCCESS)
    cross.fail("cannot reflect the module");

  ShaderReflection out;
  const spvc_entry_point* entries = nullptr;
  size_t entry_count = 0;
  spvc_compiler_get_entry_points(compiler, &entries, &entry_count);
  if (entry_count == 0) throw std::runtime_error("SPIR-V: no entry point");
  out.stage = stage_of_model(entries[0].execution_model);
  out.entry_point = entries[0].name;
  out.source_file = source_file_of(words);
  if (out.stage == VK_SHADER_STAGE_COMPUTE_BIT)
    for (unsigned axis = 0; axis < 3; ++axis)
      out.local_size[axis] = spvc_compiler_get_execution_mode_argument_by_index(compiler, SpvExecutionModeLocalSize, axis);

  spvc_resources resources = nullptr;
  if (spvc_compiler_create_shader_resources(compiler, &resources) != SPVC_SUCCESS) cross.fail("cannot list resources");
  Reflector reflector(cross, compiler);
  const spvc_reflected_resource* list = nullptr;
  size_t count = 0;
  spvc_resources_get_resource_list_for_type(resources, SPVC_RESOURCE_TYPE_PUSH_CONSTANT, &list, &count);
  if (count > 0) {
    out.push_constants = reflector.struct_of(list[0].base_type_id, 0, out);
    out.structs.push_back(*out.push_constants);
  }

  const ResourceKind kinds[] = {
      {SPVC_RESOURCE_TYPE_UNIFORM_BUFFER, VK_DESCRIPTOR_TYPE_UNIFORM_BUFFER},
      {SPVC_RESOURCE_TYPE_STORAGE_BUFFER, VK_DESCRIPTOR_TYPE_STORAGE_BUFFER},
      {SPVC_RESOURCE_TYPE_STORAGE_IMAGE, VK_DESCRIPTOR_TYPE_STORAGE_IMAGE},
      {SPVC_RESOURCE_TYPE_SAMPLED_IMAGE, VK_DESCRIPTOR_TYPE_COMBINED_IMAGE_SAMPLER},
      {SPVC_RESOURCE_TYPE_SEPARATE_IMAGE, VK_DESCRIPTOR_TYPE_SAMPLED_IMAGE},
      {SPVC_RESOURCE_TYPE_SEPARATE_SAMPLERS, VK_DESCRIPTOR_TYPE_SAMPLER},
      {SPVC_RESOURCE_TYPE_SUBPASS_INPUT, VK_DESCRIPTOR_TYPE_INPUT_ATTACHMENT},
  };
  for (const ResourceKind& kind : kinds) {
    spvc_resources_get_resource_list_for_type(resources, kind.type, &list, &count);
    for (size_t i = 0; i < count; ++i) {
      VkDescriptorType type = kind.descriptor;
      if (kind.type == SPVC_RESOURCE_TYPE_STORAGE_IMAGE)
        type = image_descriptor(compiler, list[i], type, VK_DESCRIPTOR_TYPE_STORAGE_TEXEL_BUFFER);
      if (kind.type == SPVC_RESOURCE_TYPE_SEPARATE_IMAGE)
        type = image_descriptor(compiler, list[i], type, VK_DESCRIPTOR_TYPE_UNIFORM_TEXEL_BUFFER);
      out.bindings.push_back(reflector.binding_of(list[i], type, out));
    }
  }
  std::sort(out.bindings.begin(), out.bindings.end(), [](const auto& a, const auto& b) {
    return std::pair(a.set, a.binding) < std::pair(b.set, b.binding);
  });
  return out;
}

}  // namespace avsm::gpu
