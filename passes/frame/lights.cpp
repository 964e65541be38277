#include "passes/frame/lights.h"

#include <algorithm>
#include <cmath>
#include <cstring>

#include "gpu/transfer.h"

namespace avsm::passes {

namespace {
// GpuLight::range: the falloff's end, and an area light's extent.
glm::vec4 area_extent(const scene::Light& light) {
  const float two_sided = light.two_sided ? 1.0f : 0.0f;
  switch (light.type) {
    case scene::LightType::rect: return {light.range, 0.5f * light.size.x, 0.5f * light.size.y, two_sided};
    case scene::LightType::disk: return {light.range, light.radius, 0.0f, two_sided};
    case scene::LightType::sphere: return {light.range, light.radius, 0.0f, 0.0f};
    default: return {light.range, 0.0f, 0.0f, 0.0f};
  }
}

uint32_t type_code(scene::LightType type) {
  switch (type) {
    case scene::LightType::directional: return shared::kLightDirectional;
    case scene::LightType::spot: return shared::kLightSpot;
    case scene::LightType::point: return shared::kLightPoint;
    case scene::LightType::rect: return shared::kLightRect;
    case scene::LightType::disk: return shared::kLightDisk;
    case scene::LightType::sphere: return shared::kLightSphere;
  }
  return shared::kLightDirectional;
}
}  // namespace

GpuLight to_gpu(const scene::Light& light) {
  return {glm::vec4(light.position, float(type_code(light.type))),
          glm::vec4(glm::normalize(light.direction), std::cos(light.outer_cone_angle)),
          glm::vec4(light.color * light.intensity, std::cos(light.inner_cone_angle)),
          area_extent(light)};
}

namespace {
// Every light as the shaders read it; no lights: one zero-radiance entry, which lights nothing.
std::vector<GpuLight> gpu_lights(const std::vector<scene::Light>& lights) {
  std::vector<GpuLight> data(std::max<size_t>(lights.size(), 1), GpuLight{});
  for (size_t i = 0; i < lights.size(); ++i) data[i] = to_gpu(lights[i]);
  return data;
}
}  // namespace

gpu::Buffer upload_lights(const gpu::Context& ctx, const std::vector<scene::Light>& lights) {
  return gpu::create_buffer_from(ctx, gpu_lights(lights), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT, "scene lights");
}

gpu::BufferDesc light_buffer_desc(size_t count, std::string name) {
  return {std::max<size_t>(count, 1) * sizeof(GpuLight), VK_BUFFER_USAGE_STORAGE_BUFFER_BIT,
          gpu::MemoryLocation::HostUpload, std::move(name)};
}

void write_lights(const gpu::Buffer& buffer, const std::vector<scene::Light>& lights) {
  const std::vector<GpuLight> data = gpu_lights(lights);
  std::memcpy(buffer.mapped(), data.data(), data.size() * sizeof(GpuLight));
}

}  // namespace avsm::passes
