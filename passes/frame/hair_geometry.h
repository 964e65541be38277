#pragma once
// Hair ribbon geometry in C++: shaders/common/hair_geometry.glsl compiled as C++ with
// GLM standing in for GLSL's types and built-ins. The ribbon shaders (hair_ribbon.glsl)
// and the light footprints (hair_footprint.glsl) include the same file, so tests can
// reproduce which light texels a strand segment covers, at which depth and opacity.
#include <glm/glm.hpp>

#include <cstdint>

namespace avsm::hair_geometry {

using glm::ivec2;
using glm::ivec4;
using glm::mat4;
using glm::vec2;
using glm::vec3;
using glm::vec4;
using uint = std::uint32_t;

using glm::abs;
using glm::all;
using glm::ceil;
using glm::clamp;
using glm::cross;
using glm::dot;
using glm::floor;
using glm::greaterThanEqual;
using glm::length;
using glm::max;
using glm::min;
using glm::normalize;

// Internal linkage: the GLSL functions are not inline, and several files may include
// this (each uses only some of them).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace {
#define AVSM_OUT(T) T&
#include "../../shaders/common/hair_geometry.glsl"
#undef AVSM_OUT
}  // namespace
#pragma GCC diagnostic pop

}  // namespace avsm::hair_geometry
