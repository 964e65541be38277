#pragma once
// Lights and the per-light shadow settings the scene file chooses.
#include <glm/glm.hpp>

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace avsm::scene {

enum class ShadowFilter { point, bilinear, trilinear };

// Soft shadow edges on surfaces: their lookups filtered over a kernel of texel curves
// (`box`: 2r + 1 texels wide; `gaussian`: sigma r / 2), each tap one curve evaluation.
// Volume and hair lookups keep the filter above.
enum class ShadowKernel { none, box, gaussian };

// How a light's map is built. `lists`: every caster fragment goes into per-texel lists
// (memory grows with depth complexity), optionally sorted, then resolved. `fixed`: the
// map is built straight from the casters in primitive order (the paper's fixed memory
// footprint: the map, a depth image and hair bins bounded by the segment count);
// AVSM only.
enum class ShadowBuild { lists, fixed };

// What a light's map covers. `view`: the casters the camera can see up to the shadow
// distance (directional lights; spot lights fit their cone to the casters inside it),
// moved in whole texels so that a static scene does not shimmer as the camera moves.
// `scene`: everything that casts or receives, whatever the camera sees.
enum class ShadowFit { view, scene };

// How a light's map is laid out. `dense`: resolution^2 texels (and mips), rebuilt every
// frame. `paged`: a virtual map of virtual_resolution^2 texels with mip levels, cut into
// pages of page_size^2 texels, of which only those the camera's receivers ask for are
// built, into a fixed pool, and kept across frames (passes/shadows/pages/).
enum class ShadowLayout { dense, paged };

struct ShadowSettings {
  // A shadow technique by name: avsm (adaptive volumetric shadow maps, Salvi et al.
  // 2010), uncompressed (the exact reference) or another of passes/shadows/techniques/. The
  // scene file only checks it is a name; the renderer checks it is a known one.
  std::string technique = "avsm";
  int nodes = 8;                 // 4, 8, 12 or 16
  int resolution = 1024;         // shadow map texels per side, 16 to 16384
  ShadowFilter filter = ShadowFilter::bilinear;
  ShadowKernel kernel = ShadowKernel::none;
  int kernel_radius = 1;         // texels, 1 to 4
  bool sort = true;              // sort fragments before compression (lists build)
  ShadowBuild build = ShadowBuild::lists;
  ShadowFit fit = ShadowFit::view;
  float distance = 0.0f;       // directional, fit view: how far from the camera shadows reach (0: its far plane)
  int cascades = 1;            // directional: maps split along the camera's view, 1 to 4
  float cascade_blend = 0.1f;  // the fraction of a cascade blended into the next one
  // Clustered maps (seed 004): the casters grouped by their light-space bounds, each
  // group with its own map of this resolution (at most `clusters` maps; 0 or 1: off).
  int clusters = 0;
  // Technique-specific numbers (e.g. depth bias, slab count), which each technique
  // declares with its defaults and ranges and checks; the scene file only checks
  // that they are finite numbers.
  std::map<std::string, double> parameters;
  ShadowLayout layout = ShadowLayout::dense;
  int virtual_resolution = 16384;  // paged: level-0 texels per side, a power of two, 256 to 16384 (262144 directional)
  int page_size = 64;              // paged: texels per page side: 32, 64 or 128
  double page_pool_mib = 32.0;     // paged: the light's page pool (a point light's six faces share it)
  float page_lod_bias = 0.0f;      // paged: levels added to every receiver's request (> 0: coarser)
  float page_volume_lod_bias = 1.0f;  // paged: levels added to smoke receivers' requests on top (soft shadows)
  // paged: most pages built in one frame (0: no limit); captures ignore it unless told
  // (avsm-capture --page-builds). 16: with a light that moves every frame, the default
  // scene's frame stays within 1.5x today's dense default (bench/avsm/paged.py).
  int page_builds_per_frame = 16;

  double parameter(const std::string& name, double fallback) const {
    const auto found = parameters.find(name);
    return found == parameters.end() ? fallback : found->second;
  }
};

struct Light;

// Shadow settings written over a light's own (the capture's flags, the viewer's
// edits): unset fields keep what the scene file says.
struct ShadowOverrides {
  std::optional<std::string> technique;
  std::optional<int> nodes;
  std::optional<int> resolution;
  std::optional<ShadowFilter> filter;
  std::optional<ShadowKernel> kernel;
  std::optional<int> kernel_radius;
  std::optional<bool> sort;
  std::optional<ShadowBuild> build;
  std::optional<ShadowFit> fit;
  std::optional<int> cascades;
  std::optional<int> clusters;
  std::optional<ShadowLayout> layout;
  std::optional<int> virtual_resolution;
  std::optional<int> page_size;
  std::optional<double> page_pool_mib;
  std::optional<float> page_lod_bias;
  std::optional<float> page_volume_lod_bias;
  std::optional<int> page_builds_per_frame;
  // Area lights' virtual lights (Light::virtual_lights; apply(Light&) only): what sweeps and
  // --virtual-lights vary. A light's own "shadow" block may not hold it.
  std::optional<int> virtual_lights;
  std::map<std::string, double> parameters;  // set on top of the light's own

  bool operator==(const ShadowOverrides&) const = default;
  void apply(ShadowSettings& settings) const;
  // As apply(light.shadow), but only with the settings the light's type has, so that one
  // set of overrides fits a scene of mixed lights: cascades only onto directional lights,
  // clusters not onto point lights (as the scene's "shadows".clusters is applied).
  void apply(Light& light) const;
};

// rect, disk, sphere: area lights of uniform radiance (Light::size, radius, two_sided).
enum class LightType { directional, spot, point, rect, disk, sphere };
inline bool is_area_light(LightType type) {
  return type == LightType::rect || type == LightType::disk || type == LightType::sphere;
}

// The most virtual lights (maps) an area light's soft shadows take: shared::kMaxViewsPerLight.
inline constexpr int kMaxVirtualLights = 256;

// The scene's "shadows" block: what holds for all of its lights' maps.
struct SceneShadows {
  double budget_mib = 0.0;  // all maps together (0: the device's storage buffer range)
  bool fit_budget = false;  // over the budget: lower resolutions instead of failing
  int clusters = 0;         // clustered maps for every light whose own shadow.clusters is 0
};

struct Light {
  std::string name;
  LightType type = LightType::directional;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit; the way the light travels
  glm::vec3 position{0.0f};                // spot and point
  glm::vec3 color{1.0f};                   // linear RGB
  float intensity = 1.0f;
  float inner_cone_angle = 0.0f;           // spot only: radians from the axis, full intensity inside
  float outer_cone_angle = 0.0f;           // spot only: radians from the axis, dark outside
  // Spot and point: where the light's inverse-square falloff is windowed to 0 (world
  // units; 0: no window). Point lights are shadowed out to it.
  float range = 0.0f;
  // Rect lights: a rectangle `size` wide (along shared::area_light_axes' u) and high
  // (along v) centred at `position`, facing `direction` (its normal: it emits that way,
  // both ways when two_sided), of uniform radiance color x intensity (a white Lambertian
  // surface that it fills the sky of reflects that much). Its soft shadows are the mean of
  // `virtual_lights` maps, each from a point spread over the rectangle (passes/shadows/).
  // Disk lights: a disk of `radius` facing `direction` (two_sided as a rectangle). Sphere
  // lights: a sphere of `radius`, emitting every way; its virtual lights spread over the
  // disk it shows the casters.
  glm::vec2 size{1.0f};
  float radius = 0.5f;
  bool two_sided = false;
  // 64 by measurement (bench/media/area.py, AreaLightTest): half K = 16's penumbra error for
  // 2.2x a hard spot light's cost against 1.7x; 256 costs 3.7x for no less error at the same map.
  int virtual_lights = 64;
  ShadowSettings shadow;
};

std::string_view to_string(ShadowFilter filter);
std::string_view to_string(LightType type);
std::optional<ShadowFilter> shadow_filter_from_string(std::string_view text);
std::string_view to_string(ShadowBuild build);
std::optional<ShadowBuild> shadow_build_from_string(std::string_view text);
std::string_view to_string(ShadowFit fit);
std::string_view to_string(ShadowKernel kernel);
std::optional<ShadowKernel> shadow_kernel_from_string(std::string_view text);
std::optional<ShadowFit> shadow_fit_from_string(std::string_view text);
std::string_view to_string(ShadowLayout layout);
std::optional<ShadowLayout> shadow_layout_from_string(std::string_view text);

}  // namespace avsm::scene
