#include "passes/lights.h"

#include <cmath>

#include "gpu/transfer.h"

namespace avsm::passes {

GpuLight to_gpu(const scene::Light& light) {
  bool spot = light.type == scene::LightType::spot;
  return {glm::vec4(light.position, spot ? 1.0f : 0.0f),
          glm::vec4(glm::normalize(light.direction), std::cos(light.outer_cone_angle)),
          glm::vec4(light.color * light.intensity, std::cos(light.inner_cone_angle))};
}

gpu::Buffer upload_lights(const gpu::Context& ctx, const std::vector<scene::Light>& lights) {
  std::vector<GpuLight> data;
  for (const scene::Light& light : lights) data.push_back(to_gpu(light));
  // No lights: one zero-radiance entry, which lights nothing.
  return gpu::create_buffer_from(ctx, std::move(data), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "scene lights");
}

}  // namespace avsm::passes
