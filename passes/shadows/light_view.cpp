#include "passes/shadows/light_view.h"

#include <glm/gtc/matrix_transform.hpp>

#include "lighting/hammersley.h"
#include "shared/lights.h"

#include <algorithm>
#include <array>
#include <cmath>
#include <limits>

namespace avsm::passes {
namespace {

glm::vec3 up_vector_for(const glm::vec3& direction) {
  return std::abs(direction.y) > 0.99f ? glm::vec3(1, 0, 0) : glm::vec3(0, 1, 0);
}

// The caster box, or a unit box at the origin when the scene is empty.
scene::Bounds usable_bounds(const scene::Bounds& casters) {
  if (!casters.empty()) return casters;
  scene::Bounds unit;
  unit.extend(glm::vec3(-1.0f));
  unit.extend(glm::vec3(1.0f));
  return unit;
}

std::array<glm::vec3, 8> corners(const scene::Bounds& box) {
  std::array<glm::vec3, 8> out;
  for (int corner = 0; corner < 8; ++corner)
    out[corner] = glm::vec3((corner & 1) ? box.max.x : box.min.x, (corner & 2) ? box.max.y : box.min.y,
                            (corner & 4) ? box.max.z : box.min.z);
  return out;
}

// An orthographic view along `direction` whose light-space window is the square of
// side `side` centred at `center` (light-space x, y of lookAt(0, direction)), with
// depths spanning the casters' [depth_min, depth_max] along the direction.
LightView orthographic_view(const glm::vec3& direction, const glm::mat4& rotation, glm::vec2 center, float side,
                            float depth_min, float depth_max) {
  const float span = std::max(depth_max - depth_min, 1e-3f);
  // The eye plane sits half a span in front of the casters, which lie at depths
  // [span / 2, 3 span / 2]; the depth range has a hundredth of a span of room on both
  // sides, so nothing lies at the near depth and nothing at the box faces is clipped.
  const float offset = 0.5f * span;
  const float near_depth = offset - 0.01f * span;
  const float far_depth = offset + 1.01f * span;
  const glm::vec3 eye_light(center, -(depth_min - offset));
  const glm::vec3 eye = glm::vec3(glm::transpose(rotation) * glm::vec4(eye_light, 0.0f));
  const glm::mat4 view = glm::translate(glm::mat4(1.0f), -eye_light) * rotation;
  const float h = 0.5f * side;
  LightView v;
  v.light_from_world = glm::orthoRH_ZO(-h, h, -h, h, near_depth, far_depth) * view;
  v.depth_plane = glm::vec4(direction, -glm::dot(direction, eye));
  v.eye = eye;
  v.near_depth = near_depth;
  v.far_depth = far_depth;
  v.texel_size_base = side;  // divided by the resolution in finish_view()
  return v;
}

// The light-space square around the whole caster box's bounding sphere: the same
// for every camera.
LightView directional_scene_view(const glm::vec3& direction, const scene::Bounds& casters) {
  const glm::mat4 rotation = glm::lookAtRH(glm::vec3(0.0f), direction, up_vector_for(direction));
  const float radius = std::max(0.5f * glm::length(casters.size()), 1e-3f);
  const glm::vec3 center = glm::vec3(rotation * glm::vec4(casters.center(), 1.0f));
  return orthographic_view(direction, rotation, glm::vec2(center), 2.0f * radius, -center.z - radius,
                           -center.z + radius);
}

// A perspective view from `eye` along `direction` whose window is the rectangle of
// view-plane tangents [tan_min, tan_max] (x right, y up), from a near plane just in
// front of the casters to their farthest corner (capped at `max_depth` when > 0).
LightView perspective_view(const glm::vec3& eye, const glm::vec3& direction, const glm::vec3& up, glm::vec2 tan_min,
                           glm::vec2 tan_max, const scene::Bounds& casters, float max_depth) {
  float nearest = INFINITY, farthest = 0.0f;
  for (const glm::vec3& p : corners(casters)) {
    const float d = glm::dot(p - eye, direction);
    nearest = std::min(nearest, d);
    farthest = std::max(farthest, d);
  }
  if (max_depth > 0.0f) farthest = std::min(farthest, max_depth);
  const float far_depth = std::max(farthest, 1e-2f);
  // The box's nearest corner can be behind the light; the near plane then sits close
  // to it (a thousandth of the range keeps depth precision usable).
  const float near_depth = std::clamp(nearest * 0.95f, far_depth * 1e-3f, far_depth * 0.5f);
  const glm::mat4 view = glm::lookAtRH(eye, eye + direction, up);
  const glm::mat4 projection = glm::frustumRH_ZO(tan_min.x * near_depth, tan_max.x * near_depth,
                                                 tan_min.y * near_depth, tan_max.y * near_depth, near_depth, far_depth);
  LightView v;
  v.light_from_world = projection * view;
  v.depth_plane = glm::vec4(direction, -glm::dot(direction, eye));
  v.eye = eye;
  v.perspective = true;
  v.near_depth = near_depth;
  v.far_depth = far_depth;
  v.texel_size_per_depth = tan_max.x - tan_min.x;  // divided by the resolution in finish_view()
  return v;
}

// Where a window of side `side` is centred so that it stays inside [lo, hi] when
// [lo, hi] is wider than it, and centres on [lo, hi] when it is not.
float clamp_window(float center, float side, float lo, float hi) {
  if (hi - lo <= side) return 0.5f * (lo + hi);
  return std::clamp(center, lo + 0.5f * side, hi - 0.5f * side);
}

// A spot light's cone, narrowed to the square of tangents around the casters in it
// (when every caster corner lies in front of the light; else the whole cone).
LightView spot_view(const scene::Light& light, const scene::Bounds& casters) {
  const glm::vec3 direction = glm::normalize(light.direction);
  const glm::vec3 up = up_vector_for(direction);
  const float cone = std::tan(std::clamp(light.outer_cone_angle, 0.01f, glm::radians(85.0f)));
  glm::vec2 lo(-cone), hi(cone);
  if (light.shadow.fit == scene::ShadowFit::view) {
    const glm::mat4 view = glm::lookAtRH(light.position, light.position + direction, up);
    glm::vec2 fit_lo(INFINITY), fit_hi(-INFINITY);
    bool in_front = true;
    for (const glm::vec3& p : corners(casters)) {
      const glm::vec3 q = glm::vec3(view * glm::vec4(p, 1.0f));
      if (-q.z <= 1e-3f) in_front = false;
      const glm::vec2 t = glm::vec2(q) / -q.z;
      fit_lo = glm::min(fit_lo, t);
      fit_hi = glm::max(fit_hi, t);
    }
    if (in_front) {
      fit_lo = glm::max(fit_lo, lo);
      fit_hi = glm::min(fit_hi, hi);
      // A square window, so texels stay square, inside the cone.
      const float side = std::max({fit_hi.x - fit_lo.x, fit_hi.y - fit_lo.y, 2.0f * cone * 1e-3f});
      if (side < 2.0f * cone) {
        const glm::vec2 c((fit_lo + fit_hi) * 0.5f);
        const glm::vec2 center(clamp_window(c.x, side, -cone, cone), clamp_window(c.y, side, -cone, cone));
        lo = center - 0.5f * side;
        hi = center + 0.5f * side;
      }
    }
  }
  return perspective_view(light.position, direction, up, lo, hi, casters, light.range);
}

LightView finish_view(LightView v, uint32_t resolution) {
  v.world_from_light = glm::inverse(v.light_from_world);
  v.resolution = std::max(resolution, 1u);
  v.texel_size_base /= float(v.resolution);
  v.texel_size_per_depth /= float(v.resolution);
  return v;
}

}  // namespace

LightView page_view(const LightView& virtual_view, uint32_t level, glm::uvec2 page, uint32_t page_size,
                    uint32_t max_viewport) {
  LightView v = virtual_view;
  const float scale = float(1u << level);
  v.texel_size_base *= scale;
  v.texel_size_per_depth *= scale;
  v.resolution = page_size;
  const uint32_t raster = std::max(virtual_view.resolution >> level, 1u);
  if (raster <= max_viewport) {
    v.raster_resolution = raster;
    v.raster_origin = page * page_size;
    return v;
  }
  // Clip x, y (before the divide by w, so a spot light's too) moved and scaled so that the
  // page's part of the raster's [-1, 1] becomes the whole of it.
  const float pages = float(raster / page_size);
  const glm::vec2 centre = (glm::vec2(page) + 0.5f) / pages * 2.0f - 1.0f;
  glm::mat4 crop(1.0f);
  crop[0][0] = crop[1][1] = pages;
  crop[3][0] = -centre.x * pages;
  crop[3][1] = -centre.y * pages;
  v.light_from_world = crop * virtual_view.light_from_world;
  v.world_from_light = glm::inverse(v.light_from_world);
  v.raster_resolution = 0;
  v.raster_origin = glm::uvec2(0u);
  return v;
}

UvRect light_footprint(const LightView& view, const scene::Bounds& box) {
  if (box.empty()) return {};
  UvRect rect;
  for (int corner = 0; corner < 8; ++corner) {
    const std::optional<glm::vec2> uv = view.uv(box.corner(corner));
    if (!uv) return UvRect::whole();  // behind the eye: its projection is unbounded
    rect.extend({*uv, *uv});
  }
  if (!rect.overlaps(UvRect::whole())) return {};
  return {glm::max(rect.min, glm::vec2(0.0f)), glm::min(rect.max, glm::vec2(1.0f))};
}

LightView make_light_view(const scene::Light& light, const scene::Bounds& casters, uint32_t resolution) {
  const scene::Bounds box = usable_bounds(casters);
  if (light.type == scene::LightType::point) return make_point_face_view(light, 0, casters, resolution);
  LightView v = light.type == scene::LightType::spot ? spot_view(light, box)
                                                     : directional_scene_view(glm::normalize(light.direction), box);
  return finish_view(v, resolution);
}

namespace {

// Wide enough for what an area light lights in front of it; spot_view narrows it to the casters.
constexpr float kVirtualLightCone = glm::radians(80.0f);

}  // namespace

glm::vec3 virtual_light_facing(const scene::Light& light, const scene::Bounds& casters) {
  const glm::vec3 to_casters = usable_bounds(casters).center() - light.position;
  if (light.type == scene::LightType::sphere)
    return glm::length(to_casters) > 1e-6f ? glm::normalize(to_casters) : glm::vec3(0.0f, -1.0f, 0.0f);
  const glm::vec3 n = glm::normalize(light.direction);
  return light.two_sided && glm::dot(to_casters, n) < 0.0f ? -n : n;
}

glm::vec3 virtual_light_position(const scene::Light& light, const glm::vec3& facing, uint32_t index, uint32_t count) {
  const glm::vec3 u = shared::area_light_u_axis(facing), v = glm::cross(facing, u);
  // Hammersley points, shifted half a stratum up so that they sit mid-stratum both ways.
  const glm::vec2 s =
      glm::fract(glm::vec2(lighting::hammersley(index, std::max(count, 1u))) + glm::vec2(0.0f, 0.5f / float(count)));
  if (light.type == scene::LightType::rect) {
    const glm::vec2 offset = (s - 0.5f) * light.size;
    return light.position + offset.x * u + offset.y * v;
  }
  // A disk (a sphere's: the one it shows the casters), area-uniform: radius sqrt(s.x).
  const float radius = light.radius * std::sqrt(s.x), angle = 2.0f * 3.14159265f * s.y;
  return light.position + radius * (std::cos(angle) * u + std::sin(angle) * v);
}

LightView make_virtual_light_view(const scene::Light& light, uint32_t index, uint32_t count,
                                  const scene::Bounds& casters, uint32_t resolution) {
  scene::Light spot = light;
  spot.type = scene::LightType::spot;
  spot.direction = virtual_light_facing(light, casters);
  spot.position = virtual_light_position(light, spot.direction, index, count);
  const scene::Bounds box = usable_bounds(casters);
  spot.outer_cone_angle = spot.inner_cone_angle = kVirtualLightCone;
  spot.shadow.fit = scene::ShadowFit::view;
  return finish_view(spot_view(spot, box), resolution);
}

namespace {

uint32_t virtual_lights_per_side(uint32_t count) {
  return uint32_t(std::ceil(std::sqrt(double(std::max(count, 1u)))));
}

}  // namespace

uint32_t virtual_light_tile_resolution(uint32_t resolution, uint32_t count) {
  return std::max(resolution / virtual_lights_per_side(count), kMinVirtualLightTexels);
}

namespace {

// Virtual light `index`'s map moved by a sub-texel offset of its own (the R2 sequence, within
// half a texel each way) and zoomed out by a texel to keep the casters inside. The virtual
// lights sit close together, so unjittered their texel grids line up and every map puts a
// caster's edge on the same texel boundary: their mean kept that texel's error (measured: a
// hard edge 4 cm off at 64 texels). Jittered, the errors average out over the lights.
LightView jitter_texel_grid(LightView v, uint32_t index) {
  const float texels = float(v.resolution);
  const glm::vec2 offset = glm::fract(float(index) * glm::vec2(0.7548776662f, 0.5698402910f)) - 0.5f;
  const float scale = 1.0f - 1.0f / texels;
  glm::mat4 jitter(1.0f);
  jitter[0][0] = jitter[1][1] = scale;
  jitter[3][0] = 2.0f * offset.x / texels;  // clip x += ndc shift * w
  jitter[3][1] = 2.0f * offset.y / texels;
  v.light_from_world = jitter * v.light_from_world;
  v.world_from_light = glm::inverse(v.light_from_world);
  v.texel_size_base /= scale;
  v.texel_size_per_depth /= scale;
  return v;
}

}  // namespace

uint32_t virtual_light_shared_resolution(uint32_t resolution, uint32_t count) {
  return virtual_light_tile_resolution(resolution, count) * virtual_lights_per_side(count);
}

VirtualLightMaps make_virtual_light_maps(const scene::Light& light, const scene::Bounds& casters,
                                         uint32_t resolution) {
  const uint32_t count = uint32_t(std::max(light.virtual_lights, 1));
  VirtualLightMaps maps;
  maps.tile = virtual_light_tile_resolution(resolution, count);
  float near_depth = std::numeric_limits<float>::max(), far_depth = 0.0f;
  for (uint32_t k = 0; k < count; ++k) {
    LightView view = jitter_texel_grid(make_virtual_light_view(light, k, count, casters, maps.tile), k);
    view.shared_first_texel = k * maps.tile * maps.tile;
    near_depth = std::min(near_depth, view.near_depth);
    far_depth = std::max(far_depth, view.far_depth);
    maps.views.push_back(view);
  }
  for (LightView& view : maps.views) {
    view.near_depth = near_depth;
    view.far_depth = far_depth;
  }
  maps.shared = maps.views.front();
  maps.shared.shared_first_texel = 0;
  maps.shared.resolution = virtual_light_shared_resolution(resolution, count);
  return maps;
}

float cube_face_tangent(uint32_t resolution) {
  const float inner = float(std::max<int>(int(resolution) - 2 * int(kCubeGuardTexels), 1));
  return float(resolution) / inner;
}

LightView make_point_face_view(const scene::Light& light, uint32_t face, const scene::Bounds& casters,
                               uint32_t resolution, uint32_t guard_resolution) {
  // +x -x +y -y +z -z, as shadow_cube_face() in shaders/common/shadow_lookup.glsl numbers them.
  static const std::array<glm::vec3, 6> kAxes = {glm::vec3(1, 0, 0), glm::vec3(-1, 0, 0), glm::vec3(0, 1, 0),
                                                 glm::vec3(0, -1, 0), glm::vec3(0, 0, 1), glm::vec3(0, 0, -1)};
  const glm::vec3 axis = kAxes.at(face);
  const float t = cube_face_tangent(guard_resolution != 0 ? guard_resolution : resolution);
  const LightView v = perspective_view(light.position, axis, up_vector_for(axis), glm::vec2(-t), glm::vec2(t),
                                       usable_bounds(casters), light.range);
  return finish_view(v, resolution);
}

CameraSlice camera_slice(const View& camera, float near_distance, float far_distance) {
  const glm::mat4 world_from_view = glm::inverse(camera.view);
  CameraSlice s;
  s.position = camera.camera_position;
  s.right = glm::normalize(glm::vec3(world_from_view[0]));
  s.up = glm::normalize(glm::vec3(world_from_view[1]));
  s.forward = -glm::normalize(glm::vec3(world_from_view[2]));
  s.tan_half_x = 1.0f / std::abs(camera.projection[0][0]);
  s.tan_half_y = 1.0f / std::abs(camera.projection[1][1]);
  s.near_distance = near_distance;
  s.far_distance = far_distance;
  return s;
}

LightView make_fitted_directional_view(const scene::Light& light, const scene::Bounds& casters, uint32_t resolution,
                                       const CameraSlice& slice) {
  const scene::Bounds box = usable_bounds(casters);
  const glm::vec3 direction = glm::normalize(light.direction);
  const glm::mat4 rotation = glm::lookAtRH(glm::vec3(0.0f), direction, up_vector_for(direction));
  // The casters' light-space rectangle and depths.
  glm::vec2 caster_lo(INFINITY), caster_hi(-INFINITY);
  float depth_min = INFINITY, depth_max = -INFINITY;
  for (const glm::vec3& p : corners(box)) {
    const glm::vec3 q = glm::vec3(rotation * glm::vec4(p, 1.0f));
    caster_lo = glm::min(caster_lo, glm::vec2(q));
    caster_hi = glm::max(caster_hi, glm::vec2(q));
    depth_min = std::min(depth_min, -q.z);
    depth_max = std::max(depth_max, -q.z);
  }
  // The camera slice's bounding sphere: its size depends on the field of view and the
  // slice only, never on where the camera looks, so the window's size (and its texels')
  // stays the same as the camera moves and turns.
  const float n = slice.near_distance, f = std::max(slice.far_distance, n + 1e-3f);
  glm::vec3 center_world(0.0f);
  std::array<glm::vec3, 8> slice_corners;
  for (int c = 0; c < 8; ++c) {
    const float d = (c & 4) ? f : n;
    slice_corners[c] = slice.position + slice.forward * d + slice.right * (d * slice.tan_half_x * ((c & 1) ? 1.f : -1.f)) +
                       slice.up * (d * slice.tan_half_y * ((c & 2) ? 1.f : -1.f));
  }
  // The sphere through the far corners centred on the axis (the smallest for a slice
  // with a wide far end), found along the axis so that it holds the near corners too.
  const float far_half_diagonal2 = f * f * (slice.tan_half_x * slice.tan_half_x + slice.tan_half_y * slice.tan_half_y);
  const float near_half_diagonal2 = n * n * (slice.tan_half_x * slice.tan_half_x + slice.tan_half_y * slice.tan_half_y);
  // Centre at distance z along the axis equidistant from a near and a far corner, clamped to the slice.
  float z = 0.5f * (f + n) + 0.5f * (far_half_diagonal2 - near_half_diagonal2) / (f - n);
  z = std::clamp(z, n, f);
  center_world = slice.position + slice.forward * z;
  float radius = 0.0f;
  for (const glm::vec3& p : slice_corners) radius = std::max(radius, glm::length(p - center_world));
  const float caster_side = std::max(caster_hi.x - caster_lo.x, caster_hi.y - caster_lo.y);
  const float side = std::max(std::min(2.0f * radius, caster_side), 1e-3f);
  const glm::vec2 sphere_center = glm::vec2(rotation * glm::vec4(center_world, 1.0f));
  glm::vec2 center(clamp_window(sphere_center.x, side, caster_lo.x, caster_hi.x),
                   clamp_window(sphere_center.y, side, caster_lo.y, caster_hi.y));
  if (side < caster_side) {
    // Whole texels: a window that moves with the camera moves by whole texels only, so a
    // static scene's texels cover the same world squares from frame to frame.
    const float texel = side / float(std::max(resolution, 1u));
    center = glm::floor(center / texel + 0.5f) * texel;
  }
  return finish_view(orthographic_view(direction, rotation, center, side, depth_min, depth_max), resolution);
}

std::vector<float> cascade_ends(float near_distance, float far_distance, uint32_t count) {
  // The practical split scheme (Zhang et al. 2006): half logarithmic, half uniform.
  std::vector<float> ends;
  const float n = std::max(near_distance, 1e-3f), f = std::max(far_distance, n * 1.001f);
  for (uint32_t i = 1; i <= count; ++i) {
    const float x = float(i) / float(count);
    ends.push_back(0.5f * (n * std::pow(f / n, x)) + 0.5f * (n + (f - n) * x));
  }
  return ends;
}

glm::vec3 hair_ribbon_facing_point(const LightView& light) {
  if (light.perspective) return light.eye;
  return light.eye - glm::vec3(light.depth_plane) * (1e3f * light.far_depth);
}

}  // namespace avsm::passes
