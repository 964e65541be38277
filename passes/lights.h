#pragma once
// Scene lights in the layout shaders read (shaders/common/lights.glsl), one
// storage buffer for the whole scene.
#include <glm/glm.hpp>

#include <vector>

#include "gpu/resources.h"
#include "scene/light.h"

namespace avsm::gpu {
class Context;
}

namespace avsm::passes {

// std430, 48 bytes; mirrors struct GpuLight in shaders/common/lights.glsl.
struct GpuLight {
  glm::vec4 position_type;       // xyz: position (spot); w: 0 directional, 1 spot
  glm::vec4 direction_cos_outer;  // xyz: direction the light travels; w: cos(outer cone)
  glm::vec4 radiance_cos_inner;   // rgb: colour * intensity; w: cos(inner cone)
};
static_assert(sizeof(GpuLight) == 48);

GpuLight to_gpu(const scene::Light& light);

// A device-local storage buffer with every light (at least one entry, so an
// empty scene still binds something valid).
gpu::Buffer upload_lights(const gpu::Context& ctx, const std::vector<scene::Light>& lights);

}  // namespace avsm::passes
