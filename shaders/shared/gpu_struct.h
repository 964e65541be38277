// Declaring a struct once for GLSL and C++.
//
// A shared struct is a list of members, given to GPU_STRUCT (a buffer element) or
// GPU_PUSH_CONSTANTS (a shader's push-constant block, named `pc` in GLSL):
//
//   #define GPU_LIGHT(F, A) F(vec4, position_type) A(vec4, planes, 4)
//   GPU_STRUCT(GpuLight, GPU_LIGHT)
//
// F(type, name) is a member, A(type, name, count) an array member. Comments inside
// a member list must be /* */ (the list is one macro, continued with backslashes).
// Types are GLSL's; C++ gets them from GLM, whose vectors have no std430 alignment, so
// a C++ struct can differ from the shader's when a vec3 or an array is misplaced.
// Pipeline creation catches that: each GPU_STRUCT registers its C++ layout
// (gpu/struct_layout.h), and every registered struct a shader uses is compared with
// the SPIR-V, member by member.
//
// Constants shared by both languages: GPU_CONST(uint, kName, 4u). Functions shared by
// both are written in their common subset (no GLSL-only syntax, `u` on unsigned
// literals) and marked GPU_FUNCTION, which makes them inline in C++; GLSL's built-ins
// they use (max, min) come from GLM.
#ifndef AVSM_SHARED_GPU_STRUCT_H
#define AVSM_SHARED_GPU_STRUCT_H

#ifdef __cplusplus

#include <glm/glm.hpp>

#include <cstddef>
#include <cstdint>

#include "gpu/struct_layout.h"

namespace avsm::shared {
using glm::ivec2;
using glm::ivec3;
using glm::ivec4;
using glm::mat4;
using glm::uvec2;
using glm::uvec3;
using glm::uvec4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = uint32_t;
}  // namespace avsm::shared

#define GPU_NAMESPACE_BEGIN namespace avsm::shared {
#define GPU_NAMESPACE_END }

#define GPU_FIELD_(type, name) type name;
#define GPU_ARRAY_(type, name, count) type name[count];
#define GPU_MEMBER_(type, name) {#name, uint32_t(offsetof(Self, name)), uint32_t(sizeof(type))},
#define GPU_ARRAY_MEMBER_(type, name, count) {#name, uint32_t(offsetof(Self, name)), uint32_t(sizeof(type) * (count))},

#define GPU_STRUCT(Name, MEMBERS)                                                                      \
  struct Name {                                                                                        \
    MEMBERS(GPU_FIELD_, GPU_ARRAY_)                                                                    \
    static const ::avsm::gpu::StructLayout& gpu_layout();                                              \
  };                                                                                                   \
  inline const ::avsm::gpu::StructLayout& Name::gpu_layout() {                                         \
    using Self = Name;                                                                                 \
    static const ::avsm::gpu::StructLayout& layout = ::avsm::gpu::register_struct_layout(              \
        {#Name, uint32_t(sizeof(Name)), {MEMBERS(GPU_MEMBER_, GPU_ARRAY_MEMBER_)}, __FILE__});         \
    return layout;                                                                                     \
  }                                                                                                    \
  /* Registered at start-up, so that pipelines check shaders against it before first use. */          \
  inline const ::avsm::gpu::StructLayout& Name##_registered_layout = Name::gpu_layout();
#define GPU_PUSH_CONSTANTS(Name, MEMBERS) GPU_STRUCT(Name, MEMBERS)

#define GPU_CONST(type, name, value) inline constexpr type name = value;
#define GPU_FUNCTION inline

namespace avsm::shared {
using glm::abs;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::max;
using glm::min;
using glm::normalize;
}  // namespace avsm::shared

#else  // GLSL

#define GPU_NAMESPACE_BEGIN
#define GPU_NAMESPACE_END
#define GPU_FIELD_(type, name) type name;
#define GPU_ARRAY_(type, name, count) type name[count];
#define GPU_STRUCT(Name, MEMBERS) struct Name { MEMBERS(GPU_FIELD_, GPU_ARRAY_) };
#define GPU_PUSH_CONSTANTS(Name, MEMBERS) layout(push_constant) uniform Name { MEMBERS(GPU_FIELD_, GPU_ARRAY_) } pc;
#define GPU_CONST(type, name, value) const type name = value;
#define GPU_FUNCTION

#endif

#endif
