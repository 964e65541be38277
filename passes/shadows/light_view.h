#pragma once
// How a shadowed light sees the scene: the projection its transmittance map is
// rendered with, and the light-space depth every capture, resolve and lookup
// uses. Depth is distance along the light's axis (from the light for a spot, from
// a plane in front of the casters for a directional light), linear in world
// units, so segments, nodes and receivers compare directly.
#include <glm/glm.hpp>

#include <cstdint>
#include <optional>
#include <vector>

#include "scene/bounds.h"
#include "passes/frame/view.h"
#include "passes/shadows/uv_rect.h"
#include "scene/light.h"

namespace avsm::passes {

// What sizes a map's resources (resolution^2 texels each): the setting a message names
// when one does not fit the device (gpu/device_limits.h).
inline constexpr const char* kShadowResolutionSetting = "the light's shadow.resolution (--shadow-res)";

struct LightView {
  glm::mat4 light_from_world{1.0f};  // world -> light clip space (Vulkan, z 0..1); map uv = clip.xy / w * 0.5 + 0.5
  glm::mat4 world_from_light{1.0f};  // its inverse, for per-texel rays
  glm::vec4 depth_plane{0.0f};       // depth(p) = dot(xyz, p) + w
  glm::vec3 eye{0.0f};               // the spot light, or the centre of the directional light's near face
  bool perspective = false;          // spot light
  float near_depth = 0.0f;           // depth range the casters lie in
  float far_depth = 1.0f;
  // World size of one level-0 texel at depth d: texel_size_base + texel_size_per_depth * d.
  float texel_size_base = 0.0f;
  float texel_size_per_depth = 0.0f;
  uint32_t resolution = 1;  // the map's texels per side
  // The raster the map is a window of (a paged map's page of a virtual level): the map's
  // texel (x, y) is the raster's texel raster_origin + (x, y), so a window captures
  // exactly the texels the whole raster would. 0: the map is its own raster.
  uint32_t raster_resolution = 0;
  glm::uvec2 raster_origin{0u};
  // A view whose map is a range of a map it shares (an area light's virtual light,
  // VirtualLightMaps): its texels follow one another row by row from this texel of the
  // shared map and its lists. 0 for a map of its own.
  uint32_t shared_first_texel = 0;

  uint32_t raster() const { return raster_resolution != 0 ? raster_resolution : resolution; }
  // Where the captures put its texels' lists (common/capture_lists.glsl): x its first
  // texel, y its texels per row.
  glm::uvec2 list_tile() const { return {shared_first_texel, resolution}; }
  float depth(const glm::vec3& p) const { return glm::dot(glm::vec3(depth_plane), p) + depth_plane.w; }
  float texel_size(float d) const { return texel_size_base + texel_size_per_depth * d; }
  // Where `world` lands on the map's uv square (unbounded: outside it beyond 0..1); nullopt
  // behind a spot light's eye, where the projection is unbounded.
  std::optional<glm::vec2> uv(const glm::vec3& world) const {
    const glm::vec4 clip = light_from_world * glm::vec4(world, 1.0f);
    if (clip.w <= 1e-6f) return std::nullopt;
    return glm::vec2(clip) / clip.w * 0.5f + 0.5f;
  }
};

// Page `page` (in pages) of level `level` of a paged map whose level 0 is
// `virtual_view` (its resolution the virtual one): a window of page_size texels. A level
// no wider than `max_viewport` texels is rasterized whole with the page as its render
// area (raster_origin), so that the page holds exactly the texels a dense map of that
// level would; a wider one (a directional light's clipmap levels) has a projection of
// its own, cropped to the page.
LightView page_view(const LightView& virtual_view, uint32_t level, glm::uvec2 page, uint32_t page_size,
                    uint32_t max_viewport);

// What `box` covers of the map's uv square seen from the light, conservatively (the
// rectangle around its corners' projections, clipped to the square): empty when it lies
// beside the map; the whole square when part of it is behind a spot light's eye.
UvRect light_footprint(const LightView& view, const scene::Bounds& box);

// The camera's view between two distances along its axis: what a directional light's
// map is fitted to (ShadowFit::view), one slice per cascade.
struct CameraSlice {
  glm::vec3 position{0.0f}, forward{0.0f, 0.0f, -1.0f}, right{1.0f, 0.0f, 0.0f}, up{0.0f, 1.0f, 0.0f};
  float tan_half_x = 1.0f, tan_half_y = 1.0f;
  float near_distance = 0.1f, far_distance = 100.0f;
};
CameraSlice camera_slice(const View& camera, float near_distance, float far_distance);

// Fits the light's frustum around `casters` (the scene bounds: everything that casts
// or receives), whatever the camera sees. A directional light gets an orthographic
// square around the box's bounding sphere; a spot light a perspective frustum of its
// outer cone (narrowed to the casters inside it for ShadowFit::view), from a near plane
// just in front of the casters to the farthest corner; a point light its +x face.
LightView make_light_view(const scene::Light& light, const scene::Bounds& casters, uint32_t resolution);

// Which way an area light's virtual lights face: its normal (a two-sided one's: towards the
// casters); a sphere's towards the casters.
glm::vec3 virtual_light_facing(const scene::Light& light, const scene::Bounds& casters);
// Where virtual light `index` of `count` sits on area light `light` facing `facing`:
// stratified over its shape (a Hammersley set, mapped area-uniformly onto a rectangle, a
// disk, or the disk a sphere shows the casters), so that any count covers it evenly.
glm::vec3 virtual_light_position(const scene::Light& light, const glm::vec3& facing, uint32_t index, uint32_t count);
// Virtual light `index`'s map: a spot light's at virtual_light_position, facing
// virtual_light_facing, of a 80 degree cone narrowed to the casters in front of it, as spot
// lights fit theirs.
LightView make_virtual_light_view(const scene::Light& light, uint32_t index, uint32_t count,
                                  const scene::Bounds& casters, uint32_t resolution);

// An area light's virtual lights' maps, built as one batch: one shared map of about the
// light's shadow.resolution holds a small map per virtual light (ceil(sqrt(K))^2 tiles'
// worth of texels), so the captures, sort and build run once over as many texels as
// one hard light's map, whatever K. Virtual light k's texels are the range from
// k * tile^2 on (LightView::shared_first_texel), and every map's depths span the same
// range (one build quantises them all).
struct VirtualLightMaps {
  LightView shared;              // the shared map: its view is virtual light 0's, its resolution the whole
  std::vector<LightView> views;  // per virtual light, each `tile` texels per side
  uint32_t tile = 1;
};
// The smallest virtual-light map, in texels per side: below it a map no longer
// separates the casters of the scenes area lights light.
inline constexpr uint32_t kMinVirtualLightTexels = 8;
// Each virtual light's map and the shared map, in texels per side, for `count` virtual
// lights of a light whose shadow.resolution is `resolution`.
uint32_t virtual_light_tile_resolution(uint32_t resolution, uint32_t count);
uint32_t virtual_light_shared_resolution(uint32_t resolution, uint32_t count);
VirtualLightMaps make_virtual_light_maps(const scene::Light& light, const scene::Bounds& casters,
                                         uint32_t resolution);

// A directional light's map over what the camera slice sees of the casters: a square
// of the slice's bounding-sphere size (or the casters' rectangle, when smaller) around
// their intersection, moved in whole texels, with the casters' whole depth range.
LightView make_fitted_directional_view(const scene::Light& light, const scene::Bounds& casters, uint32_t resolution,
                                       const CameraSlice& slice);

// Texels a point light's cube face keeps beyond its 90 degrees on each side, so that
// filtered lookups next to a face's edge read texels that face captured.
inline constexpr uint32_t kCubeGuardTexels = 4;
// tan(half the face's field of view) for faces of `resolution` texels.
float cube_face_tangent(uint32_t resolution);
// A point light's face `face` (+x -x +y -y +z -z): a square frustum from the light
// along that axis out to the casters (and the light's range, when it has one), with
// kCubeGuardTexels of `guard_resolution` texels (0: of `resolution`) beyond 90 degrees.
// A paged face keeps them at its coarsest level (one page), so that every level's
// filtered lookups next to the face's edge stay on it.
LightView make_point_face_view(const scene::Light& light, uint32_t face, const scene::Bounds& casters,
                               uint32_t resolution, uint32_t guard_resolution = 0);

// Camera distances where each of `count` cascades over [near, far] ends (the practical
// split scheme: half logarithmic, half uniform).
std::vector<float> cascade_ends(float near_distance, float far_distance, uint32_t count);
// The point hair ribbons turn to face in the light's captures: the spot light itself,
// or for a directional light a point far back along its direction (so ribbons face
// along it).
glm::vec3 hair_ribbon_facing_point(const LightView& light);

}  // namespace avsm::passes
