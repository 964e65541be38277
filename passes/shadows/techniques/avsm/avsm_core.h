#pragma once
// The AVSM core in C++: shaders/avsm/avsm_core.glsl compiled as C++ with GLM
// standing in for GLSL's built-ins. The GPU passes include the same file, so
// tests can check GPU results against this CPU reference bit for bit.
#include <glm/glm.hpp>

namespace avsm::core {

using glm::abs;
using glm::clamp;
using glm::max;
using glm::min;
using glm::mix;

// Internal linkage: the GLSL functions are not inline, and several files include this
// (each uses only some of them).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace {
#define AVSM_INOUT(T) T&
#define AVSM_UNROLL
#include "../../../../shaders/avsm/avsm_core.glsl"
#undef AVSM_INOUT
#undef AVSM_UNROLL
}  // namespace
#pragma GCC diagnostic pop

}  // namespace avsm::core
