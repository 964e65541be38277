#include "avsm/shadows.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <stdexcept>

#include "gpu/context.h"
#include "gpu/shader_compiler.h"
#include "passes/shadow_maps.h"
#include "passes/view.h"

#ifndef AVSM_NANOVDB_INCLUDE_DIR
#define AVSM_NANOVDB_INCLUDE_DIR "/usr/include"
#endif

namespace avsm {
namespace {

scene::ShadowFilter to_scene(ShadowFilter filter) {
  switch (filter) {
    case ShadowFilter::point: return scene::ShadowFilter::point;
    case ShadowFilter::bilinear: return scene::ShadowFilter::bilinear;
    case ShadowFilter::trilinear: return scene::ShadowFilter::trilinear;
  }
  return scene::ShadowFilter::bilinear;
}

// The facade's light as the shadow pipeline's scene light; the rest of its checks
// (nodes, resolution) are ShadowMaps' own, so both paths give the same messages.
scene::Light to_scene(const Light& light, size_t index) {
  const std::string who = "light " + std::to_string(index) + (light.name.empty() ? "" : " '" + light.name + "'");
  const float length = light.type == LightType::point ? 1.0f : glm::length(light.direction);
  if (!std::isfinite(length) || length < 1e-6f) throw std::invalid_argument(who + ": direction has no length");
  if (light.type == LightType::spot && !(light.outer_cone_radians > 0.0f && light.outer_cone_radians < 1.55f))
    throw std::invalid_argument(who + ": a spot light's outer cone must be in (0, 1.55) radians");
  scene::Light out;
  out.name = light.name;
  out.type = light.type == LightType::spot    ? scene::LightType::spot
             : light.type == LightType::point ? scene::LightType::point
                                              : scene::LightType::directional;
  out.direction = light.type == LightType::point ? glm::vec3(0.0f, -1.0f, 0.0f) : light.direction / length;
  out.position = light.position;
  out.range = light.range;
  out.shadow.fit = light.fit_to_view ? scene::ShadowFit::view : scene::ShadowFit::scene;
  out.shadow.distance = light.shadow_distance;
  out.shadow.cascades = int(light.cascades);
  out.shadow.clusters = int(light.clusters);
  out.inner_cone_angle = light.outer_cone_radians;
  out.outer_cone_angle = light.outer_cone_radians;
  out.shadow.technique = "avsm";
  out.shadow.nodes = int(light.nodes);
  out.shadow.resolution = int(light.resolution);
  out.shadow.filter = to_scene(light.filter);
  out.shadow.sort = light.sort;
  out.shadow.build = light.fixed_memory_build ? scene::ShadowBuild::fixed : scene::ShadowBuild::lists;
  return out;
}

// What the shadow parameters need of a camera: its position, and a projection whose
// [1][1] is 1 / tan(fov / 2) (a pixel's angle for trilinear filtering).
passes::View to_view(const Camera& camera) {
  passes::View view;
  view.camera_position = camera.position;
  const glm::vec3 forward = glm::length(camera.forward) > 1e-6f ? glm::normalize(camera.forward) : glm::vec3(0, 0, -1);
  view.view = glm::lookAtRH(camera.position, camera.position + forward, camera.up);
  view.projection = glm::perspectiveRH_ZO(camera.vertical_fov_radians, std::max(camera.aspect, 1e-3f),
                                          camera.near_plane, camera.far_plane);
  view.view_projection = view.projection * view.view;
  view.inverse_view_projection = glm::inverse(view.view_projection);
  view.height = std::max(camera.height_pixels, 1u);
  view.near_plane = camera.near_plane;
  view.far_plane = camera.far_plane;
  return view;
}

}  // namespace

struct Shadows::Impl {
  Impl(gpu::Context& context, const ShaderLocation& location)
      : location(location),
        library({location.glsl_root, location.spirv_root}, location.compile_from_source),
        maps(context, library) {}
  ShaderLocation location;
  gpu::ShaderLibrary library;
  passes::ShadowMaps maps;
};

Shadows::Shadows(gpu::Context& context, const ShaderLocation& shaders)
    : impl_(std::make_unique<Impl>(context, shaders)) {}

Shadows::~Shadows() = default;

void Shadows::set_lights(const std::vector<Light>& lights, const Bounds& casters_bounds,
                         const std::vector<CasterObject>& objects) {
  std::vector<scene::Light> scene_lights;
  for (size_t i = 0; i < lights.size(); ++i) scene_lights.push_back(to_scene(lights[i], i));
  impl_->maps.set_lights(scene_lights, casters_bounds, {}, objects);
}

void Shadows::set_frames_in_flight(uint32_t count) { impl_->maps.set_frames_in_flight(count); }

ShadowInputs Shadows::add_to_graph(rg::Graph& graph, const Camera& camera, const ShadowCasters& casters,
                                   uint32_t frame_slot) {
  return impl_->maps.add_to_graph(graph, to_view(camera), casters, frame_slot);
}

std::vector<LightStats> Shadows::finish_frame(uint32_t frame_slot) {
  impl_->maps.finish_frame(frame_slot);
  std::vector<LightStats> result;
  for (const passes::LightShadowStats& s : impl_->maps.frame_stats())
    result.push_back({s.light, s.nodes, s.resolution, s.mip_levels, s.map_bytes, s.capture_bytes, s.capture_requested,
                      s.capture_capacity, s.overflowed, s.grew,
                      s.fixed_build ? s.fixed_build->transient_bytes() : 0, s.maps});
  return result;
}

ShadowInputs Shadows::unshadowed_inputs() const { return impl_->maps.unshadowed_inputs(); }

const ShaderLocation& Shadows::shader_location() const { return impl_->location; }

std::vector<std::filesystem::path> Shadows::glsl_include_dirs() const {
  return gpu::glsl_include_dirs({impl_->location.glsl_root, impl_->location.spirv_root});
}

std::vector<uint32_t> Shadows::compile_glsl(const std::filesystem::path& file) const {
  gpu::ShaderCompileOptions options;
  options.include_dirs = glsl_include_dirs();
  return gpu::compile_glsl_file(file, options).spirv;
}

}  // namespace avsm
