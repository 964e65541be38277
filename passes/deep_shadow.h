#pragma once
// Lokovic & Veach compression in C++: shaders/techniques/deep_shadow.glsl compiled
// with GLM over the AVSM core's curve type (passes/avsm_core.h), so tests check the
// deep shadow map build's rule on the CPU.
#include "passes/avsm_core.h"

namespace avsm::core {

// Internal linkage: the GLSL functions are not inline, and several files include this
// (each uses only some of them).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace {
#define AVSM_INOUT(T) T&
#include "../shaders/techniques/deep_shadow.glsl"
#undef AVSM_INOUT
}  // namespace
#pragma GCC diagnostic pop

}  // namespace avsm::core
