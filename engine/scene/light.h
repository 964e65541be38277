#pragma once
// Lights and the per-light shadow settings the scene file chooses.
#include <glm/glm.hpp>

#include <map>
#include <optional>
#include <string>
#include <string_view>

namespace avsm::scene {

enum class ShadowFilter { point, bilinear, trilinear };

// How a light's map is built. `lists`: every caster fragment goes into per-texel lists
// (memory grows with depth complexity), optionally sorted, then resolved. `fixed`: the
// map is built straight from the casters in primitive order (the paper's fixed memory
// footprint: the map, a depth image and hair bins bounded by the segment count);
// AVSM only.
enum class ShadowBuild { lists, fixed };

struct ShadowSettings {
  // A shadow technique by name: avsm (adaptive volumetric shadow maps, Salvi et al.
  // 2010), uncompressed (the exact reference) or another of passes/techniques/. The
  // scene file only checks it is a name; the renderer checks it is a known one.
  std::string technique = "avsm";
  int nodes = 8;                 // 4, 8, 12 or 16
  int resolution = 1024;         // shadow map texels per side, 16 to 16384
  ShadowFilter filter = ShadowFilter::bilinear;
  bool sort = true;              // sort fragments before compression (lists build)
  ShadowBuild build = ShadowBuild::lists;
  // Technique-specific numbers (e.g. depth bias, slab count), which each technique
  // declares with its defaults and ranges and checks; the scene file only checks
  // that they are finite numbers.
  std::map<std::string, double> parameters;

  double parameter(const std::string& name, double fallback) const {
    const auto found = parameters.find(name);
    return found == parameters.end() ? fallback : found->second;
  }
};

// Shadow settings written over a light's own (the capture's flags, the viewer's
// edits): unset fields keep what the scene file says.
struct ShadowOverrides {
  std::optional<std::string> technique;
  std::optional<int> nodes;
  std::optional<int> resolution;
  std::optional<ShadowFilter> filter;
  std::optional<bool> sort;
  std::optional<ShadowBuild> build;
  std::map<std::string, double> parameters;  // set on top of the light's own

  void apply(ShadowSettings& settings) const;
};

enum class LightType { directional, spot };

struct Light {
  std::string name;
  LightType type = LightType::directional;
  glm::vec3 direction{0.0f, -1.0f, 0.0f};  // unit; the way the light travels
  glm::vec3 position{0.0f};                // spot only
  glm::vec3 color{1.0f};                   // linear RGB
  float intensity = 1.0f;
  float inner_cone_angle = 0.0f;           // spot only: radians from the axis, full intensity inside
  float outer_cone_angle = 0.0f;           // spot only: radians from the axis, dark outside
  ShadowSettings shadow;
};

std::string_view to_string(ShadowFilter filter);
std::string_view to_string(LightType type);
std::optional<ShadowFilter> shadow_filter_from_string(std::string_view text);
std::string_view to_string(ShadowBuild build);
std::optional<ShadowBuild> shadow_build_from_string(std::string_view text);

}  // namespace avsm::scene
