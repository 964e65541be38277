#include "avsm/shadows.h"

#include <glm/gtc/matrix_transform.hpp>

#include <algorithm>
#include <cmath>
#include <limits>
#include <sstream>
#include <stdexcept>

#include "gpu/context.h"
#include "gpu/shader_compiler.h"
#include "passes/camera/fog/fog_integration_pass.h"
#include "passes/camera/fog/fog_media.h"
#include "passes/camera/fog/fog_scattering_pass.h"
#include "passes/frame/frame_inputs.h"
#include "passes/frame/frames_in_flight.h"
#include "passes/frame/lights.h"
#include "passes/shadows/shadow_maps.h"
#include "passes/shadows/shadow_pass_list_builder.h"
#include "passes/frame/view.h"
#include "shared/volume.h"

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

// A precondition of one public function: throws std::invalid_argument with
// "avsm::Shadows::<function>: <what>" when it does not hold.
struct Precondition {
  const char* function;
  void require(bool holds, const std::string& what) const {
    if (!holds) throw std::invalid_argument(std::string("avsm::Shadows::") + function + ": " + what);
  }
};

bool finite(const glm::vec3& v) { return std::isfinite(v.x) && std::isfinite(v.y) && std::isfinite(v.z); }

std::string text(float value) {
  std::ostringstream out;
  out << value;
  return out.str();
}
std::string text(const glm::vec3& v) { return "(" + text(v.x) + ", " + text(v.y) + ", " + text(v.z) + ")"; }

std::string light_name(const Light& light, size_t index) {
  return "light " + std::to_string(index) + (light.name.empty() ? "" : " '" + light.name + "'");
}

// Empty (nothing given) or finite with min <= max.
void check_bounds(const Precondition& check, const Bounds& bounds, const std::string& name) {
  const bool unset = bounds.min == Bounds().min && bounds.max == Bounds().max;
  check.require(unset || (finite(bounds.min) && finite(bounds.max) && !bounds.empty()),
                name + " " + text(bounds.min) + " to " + text(bounds.max) +
                    " is not finite with min <= max (leave it default-constructed for none)");
}

// The light's own numbers; its shadow settings are ShadowMaps' (check_light_settings).
void check_light(const Precondition& check, const Light& light, size_t index) {
  const std::string who = light_name(light, index);
  const bool area = light.type == LightType::rect || light.type == LightType::disk || light.type == LightType::sphere;
  check.require(area || light.type == LightType::directional || light.type == LightType::spot ||
                    light.type == LightType::point,
                who + ": type " + std::to_string(int(light.type)) + " is not a LightType");
  if (light.type == LightType::rect)
    check.require(finite(glm::vec3(light.size, 0.0f)) && light.size.x > 0.0f && light.size.y > 0.0f,
                  who + ": size " + text(glm::vec3(light.size, 0.0f)) + " must be finite and > 0 both ways");
  if (light.type == LightType::disk || light.type == LightType::sphere)
    check.require(std::isfinite(light.radius) && light.radius > 0.0f,
                  who + ": radius " + text(light.radius) + " must be finite and > 0");
  if (light.type != LightType::point) {
    const float length = glm::length(light.direction);
    check.require(finite(light.direction) && length >= 1e-6f,
                  who + ": direction " + text(light.direction) + " must be finite and not zero");
  }
  if (light.type != LightType::directional)
    check.require(finite(light.position), who + ": position " + text(light.position) + " is not finite");
  if (light.type == LightType::spot)
    check.require(light.outer_cone_radians > 0.0f && light.outer_cone_radians < 1.55f,
                  who + ": outer_cone_radians " + text(light.outer_cone_radians) +
                      ": a spot light's outer cone must be in (0, 1.55) radians");
  check.require(std::isfinite(light.range) && light.range >= 0.0f,
                who + ": range " + text(light.range) + " must be finite and >= 0 (0: no limit)");
  check.require(std::isfinite(light.shadow_distance) && light.shadow_distance >= 0.0f,
                who + ": shadow_distance " + text(light.shadow_distance) + " must be finite and >= 0 (0: camera far)");
  check.require(light.filter == ShadowFilter::point || light.filter == ShadowFilter::bilinear ||
                    light.filter == ShadowFilter::trilinear,
                who + ": filter " + std::to_string(int(light.filter)) + " is not a ShadowFilter");
  if (light.paged)
    check.require(std::isfinite(light.page_pool_mib),
                  who + ": page_pool_mib " + text(light.page_pool_mib) + " must be finite");
  check.require(finite(light.radiance) && glm::all(glm::greaterThanEqual(light.radiance, glm::vec3(0.0f))),
                who + ": radiance " + text(light.radiance) + " must be finite and >= 0 in each component");
}

bool within(float value, float low, float high) { return std::isfinite(value) && value >= low && value <= high; }

void check_fog_medium(const Precondition& check, const FogMedium& m, const std::string& who) {
  using namespace scene;
  check.require(within(m.scattering, 0.0f, kFogMaxCoefficient),
                who + ".scattering " + text(m.scattering) + " must be 0 to 100 per metre");
  check.require(within(m.absorption, 0.0f, kFogMaxCoefficient),
                who + ".absorption " + text(m.absorption) + " must be 0 to 100 per metre");
  check.require(within(m.color.x, 0.0f, 1.0f) && within(m.color.y, 0.0f, 1.0f) && within(m.color.z, 0.0f, 1.0f),
                who + ".color " + text(m.color) + " must be in [0, 1] in each component");
  check.require(within(m.phase_g, -kFogMaxPhaseG, kFogMaxPhaseG),
                who + ".phase_g " + text(m.phase_g) + " must be -0.95 to 0.95");
}

// The scene file's ranges (scene/fog.h), with the field's name.
void check_fog(const Precondition& check, const Fog& fog) {
  using namespace scene;
  check_fog_medium(check, fog.global, "fog.global");
  check.require(within(fog.sky_light, 0.0f, kFogMaxSkyLight), "fog.sky_light " + text(fog.sky_light) + " must be 0 to 4");
  check.require(fog.grid.froxel_pixels >= kFogMinFroxelPixels && fog.grid.froxel_pixels <= kFogMaxFroxelPixels,
                "fog.grid.froxel_pixels " + std::to_string(fog.grid.froxel_pixels) + " must be 4 to 64");
  check.require(fog.grid.slices >= kFogMinSlices && fog.grid.slices <= kFogMaxSlices,
                "fog.grid.slices " + std::to_string(fog.grid.slices) + " must be 8 to 256");
  check.require(std::isfinite(fog.grid.distance) && fog.grid.distance >= 0.0f,
                "fog.grid.distance " + text(fog.grid.distance) + " must be finite and >= 0 (0: the casters' far side)");
  for (size_t i = 0; i < fog.boxes.size(); ++i) {
    const FogBox& box = fog.boxes[i];
    const std::string who = "fog.boxes[" + std::to_string(i) + "]";
    check.require(finite(box.bounds.min) && finite(box.bounds.max) &&
                      glm::all(glm::lessThan(box.bounds.min, box.bounds.max)),
                  who + ": min " + text(box.bounds.min) + " and max " + text(box.bounds.max) +
                      " must be finite with min < max on every axis");
    check_fog_medium(check, box.medium, who + ".medium");
  }
}

// A count of the API's (unsigned) as the scene light's int, without wrapping to negative.
int to_int(uint32_t count) { return int(std::min<uint32_t>(count, uint32_t(std::numeric_limits<int>::max()))); }

// The facade's light as the shadow pipeline's scene light (check_light first).
scene::Light to_scene(const Light& light) {
  scene::Light out;
  out.name = light.name;
  switch (light.type) {
    case LightType::directional: out.type = scene::LightType::directional; break;
    case LightType::spot: out.type = scene::LightType::spot; break;
    case LightType::point: out.type = scene::LightType::point; break;
    case LightType::rect: out.type = scene::LightType::rect; break;
    case LightType::disk: out.type = scene::LightType::disk; break;
    case LightType::sphere: out.type = scene::LightType::sphere; break;
  }
  out.size = light.size;
  out.radius = light.radius;
  out.two_sided = light.two_sided;
  out.virtual_lights = to_int(light.virtual_lights);
  out.direction = light.type == LightType::point ? glm::vec3(0.0f, -1.0f, 0.0f) : glm::normalize(light.direction);
  out.position = light.position;
  out.range = light.range;
  out.shadow.fit = light.fit_to_view ? scene::ShadowFit::view : scene::ShadowFit::scene;
  out.shadow.distance = light.shadow_distance;
  out.shadow.cascades = to_int(light.cascades);
  out.shadow.clusters = to_int(light.clusters);
  out.color = light.radiance;  // what the fog scatters of it
  out.intensity = 1.0f;
  out.inner_cone_angle = light.outer_cone_radians;
  out.outer_cone_angle = light.outer_cone_radians;
  out.shadow.technique = "avsm";
  out.shadow.nodes = to_int(light.nodes);
  out.shadow.resolution = to_int(light.resolution);
  out.shadow.filter = to_scene(light.filter);
  out.shadow.sort = light.sort;
  out.shadow.build = light.fixed_memory_build ? scene::ShadowBuild::fixed : scene::ShadowBuild::lists;
  out.shadow.layout = light.paged ? scene::ShadowLayout::paged : scene::ShadowLayout::dense;
  out.shadow.virtual_resolution = to_int(light.virtual_resolution);
  out.shadow.page_size = to_int(light.page_size);
  out.shadow.page_pool_mib = light.page_pool_mib;
  out.shadow.page_builds_per_frame = to_int(light.page_builds_per_frame);
  return out;
}

std::vector<scene::Light> checked_scene_lights(const std::vector<Light>& lights, const Bounds& casters_bounds,
                                               const std::vector<CasterObject>& objects) {
  const Precondition check{"set_lights"};
  std::vector<scene::Light> scene_lights;
  for (size_t i = 0; i < lights.size(); ++i) {
    check_light(check, lights[i], i);
    scene_lights.push_back(to_scene(lights[i]));
    try {
      passes::check_light_settings(scene_lights.back(), i);
    } catch (const std::invalid_argument& e) {
      check.require(false, e.what());
    }
  }
  check_bounds(check, casters_bounds, "casters_bounds");
  for (size_t i = 0; i < objects.size(); ++i) {
    const std::string who = "objects[" + std::to_string(i) + "]" + (objects[i].name.empty() ? "" : " '" + objects[i].name + "'");
    check_bounds(check, objects[i].bounds, who + ".bounds");
    check.require(objects[i].count >= 1, who + ": count is 0; an object is at least one draw, segment or volume");
  }
  return scene_lights;
}

void check_camera(const Precondition& check, const Camera& camera) {
  check.require(finite(camera.position), "camera.position " + text(camera.position) + " is not finite");
  check.require(finite(camera.forward) && glm::length(camera.forward) >= 1e-6f,
                "camera.forward " + text(camera.forward) + " must be finite and not zero");
  check.require(finite(camera.up) && glm::length(camera.up) >= 1e-6f,
                "camera.up " + text(camera.up) + " must be finite and not zero");
  check.require(glm::length(glm::cross(glm::normalize(camera.forward), glm::normalize(camera.up))) >= 1e-4f,
                "camera.up " + text(camera.up) + " is along camera.forward " + text(camera.forward));
  check.require(camera.vertical_fov_radians > 0.0f && camera.vertical_fov_radians < 3.14159f,
                "camera.vertical_fov_radians " + text(camera.vertical_fov_radians) + " must be in (0, pi)");
  check.require(camera.height_pixels >= 1, "camera.height_pixels is 0");
  check.require(std::isfinite(camera.aspect) && camera.aspect > 0.0f,
                "camera.aspect " + text(camera.aspect) + " must be finite and > 0");
  check.require(std::isfinite(camera.near_plane) && std::isfinite(camera.far_plane) && camera.near_plane > 0.0f &&
                    camera.far_plane > camera.near_plane,
                "camera.near_plane " + text(camera.near_plane) + " and far_plane " + text(camera.far_plane) +
                    " must be finite with 0 < near_plane < far_plane");
}

// A view's buffer of `stride`-byte elements, `name` (e.g. "casters.meshes.vertices"):
// given, and sized a whole, non-zero number of elements. Returns how many it holds.
uint64_t element_count(const Precondition& check, const std::string& name, VkBuffer buffer, VkDeviceSize size,
                       size_t stride, const std::string& element) {
  check.require(buffer != VK_NULL_HANDLE, name + " is VK_NULL_HANDLE");
  check.require(size > 0, name + "_size is 0: an empty buffer (give its size in bytes)");
  check.require(size % stride == 0, name + "_size " + std::to_string(size) + " bytes is not a whole number of " +
                                        element + " (stride " + std::to_string(stride) +
                                        "): the buffer must hold that layout, there is no stride to set");
  return size / stride;
}

// "(4096 bytes = 256 vertices at stride 16)"
std::string holds(VkDeviceSize size, uint64_t count, const std::string& elements, size_t stride) {
  return "(" + std::to_string(size) + " bytes = " + std::to_string(count) + " " + elements + " at stride " +
         std::to_string(stride) + ")";
}

void check_meshes(const Precondition& check, const MeshCasters& meshes) {
  if (meshes.draws.empty()) return;
  const uint64_t vertices = element_count(check, "casters.meshes.vertices", meshes.vertices, meshes.vertices_size,
                                          sizeof(CasterVertex), "CasterVertex");
  const uint64_t indices =
      element_count(check, "casters.meshes.indices", meshes.indices, meshes.indices_size, sizeof(uint32_t), "uint32");
  for (size_t i = 0; i < meshes.draws.size(); ++i) {
    const MeshDraw& draw = meshes.draws[i];
    const std::string who = "casters.meshes.draws[" + std::to_string(i) + "]";
    const uint64_t end = uint64_t(draw.first_index) + draw.index_count;
    check.require(end <= indices, who + ": indices " + std::to_string(draw.first_index) + ".." + std::to_string(end) +
                                      " exceed the index buffer " +
                                      holds(meshes.indices_size, indices, "indices", sizeof(uint32_t)));
    check.require(draw.index_count % 3 == 0,
                  who + ": index_count " + std::to_string(draw.index_count) + " is not a multiple of 3 (a triangle list)");
    check.require(int64_t(draw.vertex_offset) < int64_t(vertices),
                  who + ": vertex_offset " + std::to_string(draw.vertex_offset) + " is past the vertex buffer " +
                      holds(meshes.vertices_size, vertices, "vertices", sizeof(CasterVertex)));
    check.require(draw.alpha == passes::CasterAlpha::opaque || draw.alpha == passes::CasterAlpha::mask ||
                      draw.alpha == passes::CasterAlpha::blend,
                  who + ": alpha " + std::to_string(uint32_t(draw.alpha)) + " is not a CasterAlpha");
    check.require(draw.alpha_cutoff >= 0.0f && draw.alpha_cutoff <= 1.0f,
                  who + ": alpha_cutoff " + text(draw.alpha_cutoff) + " is not in [0, 1]");
    check.require(draw.alpha_factor >= 0.0f && draw.alpha_factor <= 1.0f,
                  who + ": alpha_factor " + text(draw.alpha_factor) + " is not in [0, 1]");
  }
}

void check_strands(const Precondition& check, const StrandCasters& strands) {
  if (strands.empty()) return;
  const uint64_t points =
      element_count(check, "casters.strands.points", strands.points, strands.points_size, sizeof(glm::vec4), "vec4");
  const uint64_t segments = element_count(check, "casters.strands.segments", strands.segments, strands.segments_size,
                                          sizeof(StrandSegment), "StrandSegment");
  element_count(check, "casters.strands.strands", strands.strands, strands.strands_size, sizeof(StrandParameters),
                "StrandParameters");
  check.require(points >= 2, "casters.strands.points holds 1 point; a segment joins two");
  const uint64_t end = uint64_t(strands.first_segment) + strands.segment_count;
  check.require(end <= segments, "casters.strands: segments " + std::to_string(strands.first_segment) + ".." +
                                     std::to_string(end) + " exceed the segment buffer " +
                                     holds(strands.segments_size, segments, "StrandSegment", sizeof(StrandSegment)));
}

void check_volumes(const Precondition& check, const VolumeCasters& volumes) {
  if (volumes.empty()) return;
  check.require(volumes.grids != VK_NULL_HANDLE, "casters.volumes.grids is VK_NULL_HANDLE");
  check.require(volumes.majorants != VK_NULL_HANDLE, "casters.volumes.majorants is VK_NULL_HANDLE");
  const uint64_t parameters = element_count(check, "casters.volumes.parameters", volumes.parameters,
                                            volumes.parameters_size, sizeof(shared::GpuVolume), "GpuVolume");
  check.require(volumes.volume_count <= parameters,
                "casters.volumes: volume_count " + std::to_string(volumes.volume_count) +
                    " exceeds the parameter buffer " +
                    holds(volumes.parameters_size, parameters, "GpuVolume", sizeof(shared::GpuVolume)));
  const bool any_atlas = volumes.atlas != VK_NULL_HANDLE || volumes.atlas_sampler != VK_NULL_HANDLE ||
                         volumes.brick_slots != VK_NULL_HANDLE;
  const bool whole_atlas = volumes.atlas != VK_NULL_HANDLE && volumes.atlas_sampler != VK_NULL_HANDLE &&
                           volumes.brick_slots != VK_NULL_HANDLE;
  check.require(!any_atlas || whole_atlas,
                "casters.volumes: the density atlas needs atlas, atlas_sampler and brick_slots together (or none)");
}

void check_objects(const Precondition& check, const std::vector<CasterObject>& objects, const ShadowCasters& casters) {
  for (size_t i = 0; i < objects.size(); ++i) {
    const CasterObject& o = objects[i];
    const uint64_t available = o.kind == CasterObject::Kind::mesh_draw ? casters.meshes.draws.size()
                               : o.kind == CasterObject::Kind::strands ? casters.strands.segment_count
                                                                       : casters.volumes.volume_count;
    const char* what = o.kind == CasterObject::Kind::mesh_draw ? "mesh draws"
                       : o.kind == CasterObject::Kind::strands ? "strand segments"
                                                               : "volumes";
    const uint64_t end = uint64_t(o.first) + o.count;
    check.require(end <= available, "the object " + std::to_string(i) + (o.name.empty() ? "" : " '" + o.name + "'") +
                                        " given to set_lights is " + what + " " + std::to_string(o.first) + ".." +
                                        std::to_string(end) + ", but the casters have " + std::to_string(available));
  }
}

// What the shadow parameters need of a camera: its position, and a projection whose
// [1][1] is 1 / tan(fov / 2) (a pixel's angle for trilinear filtering).
// (check_camera first.)
passes::View to_view(const Camera& camera) {
  passes::View view;
  view.camera_position = camera.position;
  view.view = glm::lookAtRH(camera.position, camera.position + glm::normalize(camera.forward), camera.up);
  view.projection =
      glm::perspectiveRH_ZO(camera.vertical_fov_radians, camera.aspect, camera.near_plane, camera.far_plane);
  view.view_projection = view.projection * view.view;
  view.inverse_view_projection = glm::inverse(view.view_projection);
  view.height = camera.height_pixels;
  view.width = std::max(1u, uint32_t(std::lround(float(camera.height_pixels) * camera.aspect)));
  view.near_plane = camera.near_plane;
  view.far_plane = camera.far_plane;
  return view;
}

}  // namespace

struct Shadows::Impl {
  Impl(gpu::Context& context, const ShaderLocation& location)
      : context(context),
        location(location),
        library({location.glsl_root, location.spirv_root}, location.compile_from_source),
        maps(context, library),
        fog(context),
        fog_scattering(context, library),
        fog_integration(context, library) {
    light_buffers.create(context, passes::light_buffer_desc(0, "fog lights"));  // until set_lights
  }
  gpu::Context& context;
  ShaderLocation location;
  gpu::ShaderLibrary library;
  passes::ShadowMaps maps;
  passes::FogMedia fog;
  passes::FogScatteringPass fog_scattering;
  passes::FogIntegrationPass fog_integration;
  std::vector<scene::Light> scene_lights;  // set_lights' lights as the passes take them
  passes::FrameBuffers light_buffers;      // the fog's GpuLights, per frame slot

  // The fog's two passes after the shadow work in `graph` (frame.shadows set), when on.
  void add_fog(rg::Graph& graph, passes::FrameInputs& frame) {
    frame.fog = fog.write(frame.shadows.frame_slot, frame.view);
    if (!fog.enabled()) return;
    const gpu::Buffer& lights = light_buffers[frame.shadows.frame_slot];
    passes::write_lights(lights, scene_lights);  // the slot's previous frame has completed
    frame.lights = &lights;
    frame.light_count = uint32_t(scene_lights.size());
    const rg::TextureHandle froxels = fog_scattering.add_to_graph(graph, frame);
    fog_integration.add_to_graph(graph, froxels, frame);
  }
  std::vector<CasterObject> objects;  // set_lights' (pass_list checks them against its casters)
  std::vector<Light> lights;          // set_lights', as given
  Bounds casters_bounds;
};

namespace {

const ShaderLocation& checked_location(const ShaderLocation& shaders) {
  const std::filesystem::path folder = shaders.compile_from_source ? shaders.glsl_root / "shaders"
                                                                   : shaders.spirv_root / "shaders";
  std::error_code ec;
  if (!std::filesystem::is_directory(folder, ec))
    throw std::invalid_argument("avsm::Shadows: the shader folder " + folder.string() +
                                " does not exist; check ShaderLocation (" +
                                (shaders.compile_from_source ? "glsl_root" : "spirv_root") + ")");
  return shaders;
}

}  // namespace

Shadows::Shadows(gpu::Context& context, const ShaderLocation& shaders)
    : impl_(std::make_unique<Impl>(context, checked_location(shaders))), recorder_(make_recorder(context)) {}

Shadows::~Shadows() = default;

void Shadows::check_lights(const std::vector<Light>& lights, const Bounds& casters_bounds,
                           const std::vector<CasterObject>& objects) {
  checked_scene_lights(lights, casters_bounds, objects);
}

void Shadows::check_frame(const Camera& camera, const ShadowCasters& casters, const std::vector<CasterObject>& objects) {
  const Precondition check{"pass_list"};
  check_camera(check, camera);
  check_meshes(check, casters.meshes);
  check_strands(check, casters.strands);
  check_volumes(check, casters.volumes);
  check_objects(check, objects, casters);
}

namespace {

bool same_bounds(const Bounds& a, const Bounds& b) { return a.min == b.min && a.max == b.max; }

// `after` differs from `before` in where its lights are and which way they point, at
// most. Clustered lights are grouped along their direction, so for them a turn is more.
bool only_placement_changed(const std::vector<Light>& before, const std::vector<Light>& after) {
  if (before.size() != after.size()) return false;
  for (size_t i = 0; i < before.size(); ++i) {
    Light moved = before[i];
    moved.position = after[i].position;
    moved.direction = after[i].direction;
    if (!(moved == after[i]) || after[i].clusters > 1) return false;
  }
  return true;
}

}  // namespace

void Shadows::set_lights(const std::vector<Light>& lights, const Bounds& casters_bounds,
                         const std::vector<CasterObject>& objects) {
  std::vector<scene::Light> scene_lights = checked_scene_lights(lights, casters_bounds, objects);
  if (!impl_->lights.empty() && only_placement_changed(impl_->lights, lights) &&
      same_bounds(casters_bounds, impl_->casters_bounds)) {
    // Lights that only moved keep their buffers: the next frame declared fits their maps
    // again, and frames in flight are not waited for. (No light here is clustered, so
    // the maps do not use the objects; pass_list checks the casters against them.)
    for (uint32_t i = 0; i < scene_lights.size(); ++i)
      impl_->maps.place_light(i, scene_lights[i].position, scene_lights[i].direction);
  } else {
    impl_->maps.set_lights(scene_lights, casters_bounds, {}, objects);
    impl_->light_buffers.create(impl_->context, passes::light_buffer_desc(scene_lights.size(), "fog lights"));
  }
  impl_->scene_lights = scene_lights;
  impl_->fog.set_fog(impl_->fog.fog(), casters_bounds);
  impl_->objects = objects;
  impl_->lights = lights;
  impl_->casters_bounds = casters_bounds;
}

void Shadows::set_frames_in_flight(uint32_t count) {
  impl_->maps.set_frames_in_flight(count);
  impl_->fog.set_frames_in_flight(count);
  impl_->light_buffers.set_frames(impl_->context, count);
}

void Shadows::set_fog(const Fog& fog) {
  check_fog(Precondition{"set_fog"}, fog);
  impl_->fog.set_fog(fog, impl_->casters_bounds);
}

void Shadows::set_fog_enabled(bool enabled) { impl_->fog.set_enabled(enabled); }

ShadowPassList Shadows::pass_list(const Camera& camera, const ShadowCasters& casters, uint32_t frame_slot) {
  check_frame(camera, casters, impl_->objects);
  rg::Graph graph;
  passes::FrameInputs frame;
  frame.view = to_view(camera);
  frame.shadows = impl_->maps.add_to_graph(graph, frame.view, casters, frame_slot);
  impl_->add_fog(graph, frame);
  ShadowPassList list = passes::pass_list_of(graph, &impl_->context);
  list.lookup = passes::lookup_of(frame.shadows);
  list.fog = passes::fog_lookup_of(frame.fog);
  return list;
}

std::vector<LightStats> Shadows::finish_frame(uint32_t frame_slot) {
  impl_->maps.finish_frame(frame_slot);
  std::vector<LightStats> result;
  for (const passes::LightShadowStats& s : impl_->maps.frame_stats())
    result.push_back({s.light, s.nodes, s.resolution, s.mip_levels, s.map_bytes, s.capture_bytes, s.capture_requested,
                      s.capture_capacity, s.overflowed, s.grew,
                      s.fixed_build ? s.fixed_build->transient_bytes() : 0, s.maps, s.pages});
  return result;
}

ShadowLookupResources Shadows::unshadowed_lookup() const { return passes::lookup_of(impl_->maps.unshadowed_inputs()); }

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
