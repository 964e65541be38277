#version 460
// How well the shadow maps' resolution matches the camera's (issue 33's figure: the
// texel a lookup reads is at most 1.5 screen pixels wide): for every camera pixel and
// every light, at the opaque surface in the depth buffer, where the light reaches it
// (facing the light, inside a spot's cone, inside the map):
//  - the level the surface lookup reads (shadow_lookup_levels(): the finest resident
//    one for a paged map; 0 for a dense one, unless it is trilinear), with its blend;
//  - the widest a texel of that level is on screen, in pixels: the texel's width in
//    map uv over the smallest singular value of the map uv's screen Jacobian (found
//    from the neighbouring depth texels, in the same map), so a texel stretched by a
//    grazing light counts at its longest;
//  - how many texels a map that just meets the target there would spend on the pixel.
// Hair and smoke receivers are not measured.
#extension GL_GOOGLE_include_directive : require

#include "common/lights.glsl"
#define AVSM_SHADOW_BINDING 3
#include "common/shadow_lookup.glsl"
#include "shared/passes/camera/quality/shadow_resolution.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D depth_texture;
#define DEPTH_SURFACE_TEXTURE depth_texture
#include "common/depth_surface.glsl"
layout(std430, binding = 1) writeonly buffer Results { PixelShadowResolution results[]; };  // [light * width * height + y * width + x]
layout(std430, binding = 2) readonly buffer Lights { GpuLight lights[]; };

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.image_size))) return;
  uint pixel_count = pc.image_size.x * pc.image_size.y;
  uint pixel_index = uint(pixel.y) * pc.image_size.x + uint(pixel.x);

  DepthCamera camera = DepthCamera(pc.inverse_view_projection, pc.image_size);
  vec3 p;
  bool has_surface = depth_surface_point(camera, pixel, p);
  vec3 to_camera = normalize(pc.camera_position - p);
  vec3 step_x, step_y;
  bool has_steps = has_surface && depth_surface_step(camera, pixel, p, ivec2(1, 0), step_x) &&
                   depth_surface_step(camera, pixel, p, ivec2(0, 1), step_y);
  look_up_with_pixel_steps(has_steps ? step_x : vec3(0.0), has_steps ? step_y : vec3(0.0));  // as the opaque pass's derivatives
  vec3 normal = has_surface ? depth_surface_normal(camera, pixel, p, to_camera) : to_camera;

  for (uint light = 0u; light < pc.light_count; ++light) {
    vec3 to_light;
    vec3 radiance = light_radiance(lights[light], p, to_light);
    uint record = light_map_record_at(light, p);
    GpuShadow s = shadows[record];
    vec3 q = shadow_surface_point(s, p, normal, to_light);
    vec2 uv = shadow_map_uv(s, q);
    bool counts = has_steps && any(greaterThan(radiance, vec3(0.0))) && dot(normal, to_light) > 0.0 &&
                  s.technique != kShadowNone && all(greaterThanEqual(uv, vec2(0.0))) && all(lessThanEqual(uv, vec2(1.0)));
    ShadowLevels read = shadow_lookup_levels(s, q, uv, shadow_light_depth(s, q), kReceiverSurface);
    float texel_uv = shadow_read_texel_uv(s, read);
    vec2 uv_x = shadow_map_uv(s, q + step_x) - uv, uv_y = shadow_map_uv(s, q + step_y) - uv;
    float stretch = shadow_smallest_stretch(uv_x, uv_y);
    float matched_texel_uv = kPagedTexelPixels * stretch;
    PixelShadowResolution result;
    result.level = counts ? float(read.first) + (read.count == 2 ? read.blend : 0.0) : -1.0;
    result.texel_pixels = stretch > 0.0 ? texel_uv / stretch : 1e30;
    result.needed_texels = stretch > 0.0 ? abs(uv_x.x * uv_y.y - uv_x.y * uv_y.x) / (matched_texel_uv * matched_texel_uv) : 0.0;
    result.map = record;
    result.paged = shadow_is_paged(s) ? 1u : 0u;
    uint entry = light * pixel_count + pixel_index;  // member by member: glslang 11 emits an invalid store for the whole struct
    results[entry].level = result.level;
    results[entry].texel_pixels = result.texel_pixels;
    results[entry].needed_texels = result.needed_texels;
    results[entry].map = result.map;
    results[entry].paged = result.paged;
  }
}
