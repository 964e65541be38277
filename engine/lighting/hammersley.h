#pragma once
// Hammersley points: a fixed, low-discrepancy set of `count` points in the unit square
// (the index in even steps along x, its base-2 radical inverse along y). The LTC fit
// integrates its error with them (ltc.cpp), and a rect light's virtual lights sit at them
// (passes/shadows/light_view.cpp).
#include <glm/glm.hpp>

#include <cstdint>

namespace avsm::lighting {

// The bits of `i` mirrored about the binary point: 0.5, 0.25, 0.75, 0.125, ...
inline double radical_inverse(uint32_t bits) {
  bits = (bits << 16u) | (bits >> 16u);
  bits = ((bits & 0x55555555u) << 1u) | ((bits & 0xAAAAAAAAu) >> 1u);
  bits = ((bits & 0x33333333u) << 2u) | ((bits & 0xCCCCCCCCu) >> 2u);
  bits = ((bits & 0x0F0F0F0Fu) << 4u) | ((bits & 0xF0F0F0F0u) >> 4u);
  bits = ((bits & 0x00FF00FFu) << 8u) | ((bits & 0xFF00FF00u) >> 8u);
  return double(bits) * 2.3283064365386963e-10;  // / 2^32
}

// Point i of `count`, in [0, 1)^2.
inline glm::dvec2 hammersley(uint32_t i, uint32_t count) { return {(i + 0.5) / count, radical_inverse(i)}; }

}  // namespace avsm::lighting
