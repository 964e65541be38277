#pragma once
// The viewer's edits to a loaded scene, kept apart from it so they survive a
// reload of the scene file: each field is set only once the user touched it, and
// apply() writes the set ones over whatever the files say (LiveRenderer calls it
// after every load through set_scene_edit).
#include <glm/glm.hpp>

#include <optional>
#include <vector>

#include "scene/scene.h"

namespace avsm::viewer {

// The shadow fields come from scene::ShadowOverrides (shared with avsm-capture's flags).
struct LightOverride : scene::ShadowOverrides {
  // Off: the light contributes nothing (intensity 0); its shadow map is still built,
  // so its timings and curves stay comparable.
  std::optional<bool> enabled;
  std::optional<glm::vec3> position;   // spot lights
  std::optional<glm::vec3> direction;  // normalised when applied
  // Area lights: their shape (another area light type; others are ignored), a rect's size, a
  // disk's or sphere's radius (at least kMinAreaLightExtent), the virtual lights (clamped
  // to 1..256).
  std::optional<scene::LightType> area_shape;
  std::optional<glm::vec2> size;
  std::optional<float> radius;
  std::optional<int> virtual_lights;
};

// The smallest area-light extent an edit gives, in metres.
inline constexpr float kMinAreaLightExtent = 0.01f;

struct VolumeOverride {
  std::optional<float> extinction_scale;
  std::optional<glm::vec3> albedo;
  std::optional<scene::MultipleScattering> multiple_scattering;  // clamped to the scene file's ranges
  std::optional<float> sky_light;
};

// The fog's global medium and its switch (its boxes and grid stay the file's).
struct FogOverride {
  std::optional<bool> enabled;  // off: no fog; on over a scene without fog: a thin global one
  std::optional<float> scattering, absorption;  // per metre, clamped to 0..100
  std::optional<float> phase_g;                 // clamped to -0.95..0.95
  std::optional<float> sky_light;               // clamped to 0..4
};

struct SceneOverrides {
  std::vector<LightOverride> lights;    // by light index; lights beyond the scene's are ignored
  std::vector<VolumeOverride> volumes;  // by volume index
  // Every hair groom: strand opacities (clamped to [0, 1]) and widths are multiplied.
  float hair_opacity_scale = 1.0f;
  float hair_width_scale = 1.0f;
  scene::VolumeShadingOverrides volume_shading;  // the avsm-viewer flags, then the panel
  FogOverride fog;

  LightOverride& light(size_t index);
  VolumeOverride& volume(size_t index);
  void apply(scene::Scene& scene) const;
};

}  // namespace avsm::viewer
