#pragma once
// The C++ side of a struct that C++ and GLSL share. Shared structs are written once,
// in shaders/shared/*.h (compiled as both languages, see shaders/shared/gpu_struct.h);
// each registers its C++ layout here under its GLSL name, and pipeline creation
// checks every registered struct a shader uses against the shader's SPIR-V layout.
#include <cstdint>
#include <string>
#include <vector>

namespace avsm::gpu {

struct MemberLayout {
  const char* name;
  uint32_t offset;
  uint32_t size;  // bytes, the whole array for array members
};

struct StructLayout {
  const char* name;         // as in GLSL
  uint32_t size;            // sizeof in C++
  std::vector<MemberLayout> members;
  const char* declared_in;  // the shared header
};

// Returns the registered layout (the first registration of a name wins; a second,
// different one is a programming error and throws).
const StructLayout& register_struct_layout(const StructLayout& layout);
// Null when C++ declares no struct of that GLSL name.
const StructLayout* find_struct_layout(const std::string& name);

}  // namespace avsm::gpu
