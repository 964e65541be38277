#include "viewer/scene_overrides.h"

#include <algorithm>

#include "passes/shadows/shadow_settings.h"

namespace avsm::viewer {

namespace {

void apply_light(const LightOverride& o, scene::Light& light) {
  passes::apply_shadow_overrides(o, light);
  if (o.enabled && !*o.enabled) light.intensity = 0.0f;
  if (o.position) light.position = *o.position;
  if (o.direction && glm::length(*o.direction) > 0.0f) light.direction = glm::normalize(*o.direction);
  if (!scene::is_area_light(light.type)) return;
  if (o.area_shape && scene::is_area_light(*o.area_shape)) light.type = *o.area_shape;
  if (o.size) light.size = glm::max(*o.size, glm::vec2(kMinAreaLightExtent));
  if (o.radius) light.radius = std::max(*o.radius, kMinAreaLightExtent);
  if (o.virtual_lights) light.virtual_lights = std::clamp(*o.virtual_lights, 1, scene::kMaxVirtualLights);
}

void apply_volume(const VolumeOverride& o, scene::Volume& volume) {
  if (o.extinction_scale) volume.extinction_scale = std::max(*o.extinction_scale, 0.0f);
  if (o.albedo) volume.albedo = glm::clamp(*o.albedo, 0.0f, 1.0f);
  if (o.multiple_scattering) {
    scene::MultipleScattering& m = volume.multiple_scattering;
    m.octaves = std::clamp(o.multiple_scattering->octaves, 1, 8);
    m.attenuation = std::clamp(o.multiple_scattering->attenuation, 0.01f, 1.0f);
    m.contribution = std::clamp(o.multiple_scattering->contribution, 0.0f, 1.0f);
  }
  if (o.sky_light) volume.sky_light = std::clamp(*o.sky_light, 0.0f, 4.0f);
}

// The fog a viewer switches on over a scene without one.
constexpr float kSwitchedOnFogScattering = 0.05f;

void apply_fog(const FogOverride& o, scene::Fog& fog) {
  if (o.enabled && !*o.enabled) {
    fog.global = {};
    fog.boxes.clear();
    return;
  }
  if (o.enabled && !fog.enabled()) fog.global.scattering = kSwitchedOnFogScattering;
  if (o.scattering) fog.global.scattering = std::clamp(*o.scattering, 0.0f, 100.0f);
  if (o.absorption) fog.global.absorption = std::clamp(*o.absorption, 0.0f, 100.0f);
  if (o.phase_g) fog.global.phase_g = std::clamp(*o.phase_g, -0.95f, 0.95f);
  if (o.sky_light) fog.sky_light = std::clamp(*o.sky_light, 0.0f, 4.0f);
}

void scale_hair(scene::HairGroom& groom, float opacity_scale, float width_scale) {
  for (float& opacity : groom.strand_opacity) opacity = std::clamp(opacity * opacity_scale, 0.0f, 1.0f);
  for (float& width : groom.strand_width) width *= width_scale;
}

}  // namespace

LightOverride& SceneOverrides::light(size_t index) {
  if (lights.size() <= index) lights.resize(index + 1);
  return lights[index];
}

VolumeOverride& SceneOverrides::volume(size_t index) {
  if (volumes.size() <= index) volumes.resize(index + 1);
  return volumes[index];
}

void SceneOverrides::apply(scene::Scene& scene) const {
  for (size_t i = 0; i < lights.size() && i < scene.lights.size(); ++i) apply_light(lights[i], scene.lights[i]);
  for (size_t i = 0; i < volumes.size() && i < scene.volumes.size(); ++i) apply_volume(volumes[i], scene.volumes[i]);
  if (hair_opacity_scale != 1.0f || hair_width_scale != 1.0f)
    for (scene::HairGroom& groom : scene.hair) scale_hair(groom, hair_opacity_scale, hair_width_scale);
  volume_shading.apply(scene.volume_shading);
  apply_fog(fog, scene.fog);
}

}  // namespace avsm::viewer
