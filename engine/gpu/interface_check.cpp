// Pipeline creation's check of the structs C++ and GLSL share (see gpu/pipeline.h).
#include <string>

#include "gpu/pipeline.h"

namespace avsm::gpu {
namespace {

const char* stage_name(VkShaderStageFlagBits stage) {
  switch (stage) {
    case VK_SHADER_STAGE_VERTEX_BIT: return "vertex shader";
    case VK_SHADER_STAGE_GEOMETRY_BIT: return "geometry shader";
    case VK_SHADER_STAGE_FRAGMENT_BIT: return "fragment shader";
    default: return "compute shader";
  }
}

// "shaders/passes/x.comp", or a shadow technique's "passes/shadows/techniques/x/y.comp",
// out of an absolute path.
std::string relative_to_repository(std::string path) {
  for (const char* root : {"shaders/", "passes/"})
    if (size_t at = path.rfind(root); at != std::string::npos) return path.substr(at);
  return path;
}

std::string shader_name(const std::string& pipeline, const ShaderReflection& stage) {
  std::string file = relative_to_repository(stage.source_file);
  if (file.empty()) file = stage_name(stage.stage);
  return "shader '" + file + "' (pipeline '" + pipeline + "')";
}

std::string difference(const ReflectedStruct& shader, const StructLayout& cpp) {
  if (shader.members.size() != cpp.members.size())
    return "has " + std::to_string(shader.members.size()) + " members in the shader and " +
           std::to_string(cpp.members.size()) + " in C++";
  for (size_t i = 0; i < cpp.members.size(); ++i) {
    const ReflectedMember& s = shader.members[i];
    const MemberLayout& c = cpp.members[i];
    const std::string member = "member " + std::to_string(i) + " '" + c.name + "'";
    if (s.name != c.name) return member + " is '" + s.name + "' in the shader";
    if (s.offset != c.offset)
      return member + " is at byte " + std::to_string(s.offset) + " in the shader and " + std::to_string(c.offset) +
             " in C++";
    if (s.size != 0 && s.size != c.size)
      return member + " takes " + std::to_string(s.size) + " bytes in the shader and " + std::to_string(c.size) +
             " in C++";
  }
  if (shader.size != cpp.size)
    return "takes " + std::to_string(shader.size) + " bytes in the shader and " + std::to_string(cpp.size) + " in C++";
  return {};
}

}  // namespace

void check_shared_structs(const std::string& pipeline, const std::vector<ShaderReflection>& stages) {
  for (const ShaderReflection& stage : stages) {
    if (stage.push_constants && !find_struct_layout(stage.push_constants->name))
      throw InterfaceError(shader_name(pipeline, stage) + ": push-constant block '" + stage.push_constants->name +
                           "' has no C++ declaration; declare it once with GPU_PUSH_CONSTANTS in shaders/shared/");
    for (const ReflectedStruct& s : stage.structs) {
      const StructLayout* cpp = find_struct_layout(s.name);
      if (!cpp) continue;  // a shader-only struct
      if (std::string problem = difference(s, *cpp); !problem.empty())
        throw InterfaceError(shader_name(pipeline, stage) + ": struct " + s.name + " " + problem + " (declared in " +
                             relative_to_repository(cpp->declared_in) + ")");
    }
  }
}

}  // namespace avsm::gpu
