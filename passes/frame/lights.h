#pragma once
// Scene lights in the layout shaders read (shaders/shared/lights.h), one
// storage buffer for the whole scene.
#include <glm/glm.hpp>

#include <string>
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

// A host-written storage buffer for `count` lights (at least one entry, as above), to
// rewrite each frame (one per frame slot: passes/frame/frames_in_flight.h).
gpu::BufferDesc light_buffer_desc(size_t count, std::string name);
// Writes every light into `buffer` (light_buffer_desc's, for at least lights.size()), its
// one entry lighting nothing when there are none. The frame that last read it has completed.
void write_lights(const gpu::Buffer& buffer, const std::vector<scene::Light>& lights);

}  // namespace avsm::passes
