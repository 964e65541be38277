#include "scene/light.h"

#include <array>
#include <utility>

namespace avsm::scene {
namespace {

constexpr std::array<std::pair<ShadowFilter, std::string_view>, 3> kFilters = {{
    {ShadowFilter::point, "point"},
    {ShadowFilter::bilinear, "bilinear"},
    {ShadowFilter::trilinear, "trilinear"},
}};

template <class Table, class Enum>
std::string_view name_of(const Table& table, Enum value) {
  for (const auto& [candidate, name] : table)
    if (candidate == value) return name;
  return "?";
}

template <class Enum, class Table>
std::optional<Enum> value_of(const Table& table, std::string_view text) {
  for (const auto& [value, name] : table)
    if (name == text) return value;
  return std::nullopt;
}

constexpr std::array<std::pair<ShadowBuild, std::string_view>, 2> kBuilds = {{
    {ShadowBuild::lists, "lists"},
    {ShadowBuild::fixed, "fixed"},
}};

constexpr std::array<std::pair<ShadowKernel, std::string_view>, 3> kKernels = {{
    {ShadowKernel::none, "none"},
    {ShadowKernel::box, "box"},
    {ShadowKernel::gaussian, "gaussian"},
}};

}  // namespace

std::string_view to_string(ShadowKernel kernel) { return name_of(kKernels, kernel); }
std::optional<ShadowKernel> shadow_kernel_from_string(std::string_view text) {
  return value_of<ShadowKernel>(kKernels, text);
}
std::string_view to_string(ShadowBuild build) { return name_of(kBuilds, build); }
std::optional<ShadowBuild> shadow_build_from_string(std::string_view text) { return value_of<ShadowBuild>(kBuilds, text); }
std::string_view to_string(ShadowFilter filter) { return name_of(kFilters, filter); }
std::string_view to_string(LightType type) {
  switch (type) {
    case LightType::directional: return "directional";
    case LightType::spot: return "spot";
    case LightType::point: return "point";
    case LightType::rect: return "rect";
    case LightType::disk: return "disk";
    case LightType::sphere: return "sphere";
  }
  return "?";
}
std::string_view to_string(ShadowFit fit) { return fit == ShadowFit::view ? "view" : "scene"; }
std::optional<ShadowFit> shadow_fit_from_string(std::string_view text) {
  if (text == "view") return ShadowFit::view;
  if (text == "scene") return ShadowFit::scene;
  return std::nullopt;
}
std::string_view to_string(ShadowLayout layout) { return layout == ShadowLayout::dense ? "dense" : "paged"; }
std::optional<ShadowLayout> shadow_layout_from_string(std::string_view text) {
  if (text == "dense") return ShadowLayout::dense;
  if (text == "paged") return ShadowLayout::paged;
  return std::nullopt;
}
std::optional<ShadowFilter> shadow_filter_from_string(std::string_view text) {
  return value_of<ShadowFilter>(kFilters, text);
}

void ShadowOverrides::apply(ShadowSettings& settings) const {
  if (technique) settings.technique = *technique;
  if (nodes) settings.nodes = *nodes;
  if (resolution) settings.resolution = *resolution;
  if (filter) settings.filter = *filter;
  if (kernel) settings.kernel = *kernel;
  if (kernel_radius) settings.kernel_radius = *kernel_radius;
  if (sort) settings.sort = *sort;
  if (build) settings.build = *build;
  if (fit) settings.fit = *fit;
  if (cascades) settings.cascades = *cascades;
  if (clusters) settings.clusters = *clusters;
  if (layout) settings.layout = *layout;
  if (virtual_resolution) settings.virtual_resolution = *virtual_resolution;
  if (page_size) settings.page_size = *page_size;
  if (page_pool_mib) settings.page_pool_mib = *page_pool_mib;
  if (page_lod_bias) settings.page_lod_bias = *page_lod_bias;
  if (page_volume_lod_bias) settings.page_volume_lod_bias = *page_volume_lod_bias;
  if (page_builds_per_frame) settings.page_builds_per_frame = *page_builds_per_frame;
  for (const auto& [name, value] : parameters) settings.parameters[name] = value;
}

void ShadowOverrides::apply(Light& light) const {
  ShadowOverrides fitting = *this;
  if (light.type != LightType::directional) fitting.cascades.reset();
  if (light.type == LightType::point || is_area_light(light.type)) fitting.clusters.reset();
  fitting.apply(light.shadow);
  if (virtual_lights && is_area_light(light.type)) light.virtual_lights = *virtual_lights;
}

}  // namespace avsm::scene
