#pragma once
// The opacity and Fourier opacity map math in C++: passes/shadows/techniques/opacity_maps.glsl
// compiled with GLM, so tests check the GPU maps against the same code.
#include <glm/glm.hpp>

#include <cmath>

namespace avsm::opacity {

using glm::clamp;
using glm::max;
using glm::min;
using glm::mix;
using std::cos;
using std::exp;
using std::floor;
using std::log;
using std::sin;

// Internal linkage: the GLSL functions are not inline, and several files include this
// (each uses only some of them).
#pragma GCC diagnostic push
#pragma GCC diagnostic ignored "-Wunused-function"
namespace {
#include "opacity_maps.glsl"
}  // namespace
#pragma GCC diagnostic pop

}  // namespace avsm::opacity
