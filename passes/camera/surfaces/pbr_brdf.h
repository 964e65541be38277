#pragma once
// The glTF metallic-roughness BRDF in C++: shaders/common/pbr_brdf.glsl compiled as C++
// with GLM standing in for GLSL's types and built-ins. The opaque pass's shader includes
// the same file, so tests can evaluate exactly what the GPU shades.
#include <glm/glm.hpp>

namespace avsm::pbr {

using glm::vec2;
using glm::vec3;
using glm::vec4;

using glm::clamp;
using glm::dot;
using glm::exp2;
using glm::max;
using glm::min;
using glm::mix;
using glm::normalize;
using glm::sqrt;

// Internal linkage: the GLSL functions are not inline, and several files may include
// this (each uses only some of them).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace {
#include "../../../shaders/common/pbr_brdf.glsl"
}  // namespace
#pragma GCC diagnostic pop

}  // namespace avsm::pbr
