#pragma once
// The AVSM core in C++: shaders/avsm/avsm_core.glsl compiled as C++ with GLM
// standing in for GLSL's built-ins. The GPU passes include the same file, so
// tests can check GPU results against this CPU reference bit for bit.
#include <glm/glm.hpp>

namespace avsm::core {

using glm::abs;
using glm::max;
using glm::min;
using glm::mix;

#define AVSM_INOUT(T) T&
#include "../shaders/avsm/avsm_core.glsl"
#undef AVSM_INOUT

}  // namespace avsm::core
