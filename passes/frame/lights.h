#pragma once
// Scene lights in the layout shaders read (shaders/shared/lights.h), one
// storage buffer for the whole scene.
#include <glm/glm.hpp>

#include <vector>

#include "gpu/resources.h"
#include "shared/lights.h"
#include "scene/light.h"

namespace avsm::gpu {
class Context;
}

namespace avsm::passes {

using shared::GpuLight;  // shaders/shared/lights.h

GpuLight to_gpu(const scene::Light& light);

// A device-local storage buffer with every light (at least one entry, so an
// empty scene still binds something valid).
gpu::Buffer upload_lights(const gpu::Context& ctx, const std::vector<scene::Light>& lights);

}  // namespace avsm::passes
