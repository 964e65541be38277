#version 460
// Shadow quality against the exact reference (avsm-capture --compare-to uncompressed):
// for every camera pixel and every light, the technique's transmittance and the
// exact one (reference_light_transmittance(), the light's capture lists) at the
// receivers the pixel sees:
//  - the opaque surface in the depth buffer, moved along its normal as the opaque
//    pass does (surface_lookup_point); the normal comes from the neighbouring
//    depth texels. Counted where the light reaches it (facing the light, inside a
//    spot's cone), since elsewhere the shadow cannot show;
//  - smoke: up to pc.smoke_samples evenly spaced points of the pixel ray inside
//    each volume's support, in front of the surface, where the density is > 0 and
//    the light reaches.
// Hair is not measured (it writes no depth). Results per light and pixel:
//   x: |T - T_ref| at the surface, or -1 when the pixel has no (lit) surface
//   y: sum of |T - T_ref| over the smoke receivers, z: their maximum, w: their count.
#extension GL_GOOGLE_include_directive : require

#define AVSM_VOLUME_BINDING_NANOVDB 2
#define AVSM_VOLUME_BINDING_MAJORANTS 3
#define AVSM_VOLUME_BINDING_PARAMETERS 4
#include "common/volume.glsl"
#include "common/lights.glsl"
#define AVSM_SHADOW_BINDING 6
#include "common/shadow_lookup.glsl"
#include "shared/passes/camera/quality/shadow_quality.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0) uniform sampler2D depth_texture;
#define DEPTH_SURFACE_TEXTURE depth_texture
#include "common/depth_surface.glsl"
layout(std430, binding = 1) buffer Errors { PixelShadowError errors[]; };  // [light * width * height + y * width + x]
layout(std430, binding = 5) readonly buffer Lights { GpuLight lights[]; };


bool lit(vec3 radiance) { return any(greaterThan(radiance, vec3(0.0))); }

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.image_size))) return;
  uint pixel_count = pc.image_size.x * pc.image_size.y;
  uint pixel_index = uint(pixel.y) * pc.image_size.x + uint(pixel.x);

  DepthCamera camera = DepthCamera(pc.inverse_view_projection, pc.image_size);
  float depth = texelFetch(depth_texture, pixel, 0).r;
  bool has_surface = depth < kFarDepth;
  vec3 far_point = depth_pixel_point(camera, pixel, depth);
  vec3 origin = pc.camera_position;
  float t_max = length(far_point - origin);
  vec3 direction = t_max > 0.0 ? (far_point - origin) / t_max : vec3(0.0, 0.0, -1.0);
  vec3 normal = has_surface ? depth_surface_normal(camera, pixel, far_point, -direction) : vec3(0.0);

  // Each pixel's errors are kept in its own entries of `errors` as they add up (no
  // private array per light, so any number of lights). The lookups run for every
  // pixel, and receivers that do not count are dropped afterwards, so that no lookup
  // sits in a branch only some lanes take.
  uint light_count = pc.light_count;
  for (uint light = 0u; light < light_count; ++light) {
    vec3 to_light;
    vec3 radiance = light_radiance(lights[light], far_point, to_light);
    bool counts = has_surface && lit(radiance) && dot(normal, to_light) > 0.0;
    vec3 q = surface_lookup_point(light, far_point, has_surface ? normal : to_light, to_light);
    float error = abs(light_transmittance(light, q) - reference_light_transmittance(light, q));
    errors[light * pixel_count + pixel_index] = PixelShadowError(counts ? error : -1.0, 0.0, 0.0, 0.0);
  }

  for (uint v = 0u; v < pc.volume_count; ++v) {
    float t_enter, t_exit;
    bool hit = t_max > 0.0 && volume_interval(v, origin, direction, t_max, t_enter, t_exit);
    if (!hit) t_enter = t_exit = 0.0;
    GpuVolume volume = volumes[v];
    DensityReader reader = make_density_reader(volume);
    vec3 index_origin = (volume.index_from_world * vec4(origin, 1.0)).xyz;
    vec3 index_direction = mat3(volume.index_from_world) * direction;
    for (uint k = 0u; k < pc.smoke_samples; ++k) {
      float t = mix(t_enter, t_exit, (float(k) + 0.5) / float(pc.smoke_samples));
      bool inside = hit && sample_density(reader, index_origin + t * index_direction) > 0.0;
      vec3 p = origin + t * direction;
      for (uint light = 0u; light < light_count; ++light) {
        vec3 to_light;
        bool counts = inside && lit(light_radiance(lights[light], p, to_light));
        float error = abs(light_transmittance(light, p) - reference_light_transmittance(light, p));
        if (counts) {  // member by member: glslang 11 emits an invalid store for the whole struct
          uint entry = light * pixel_count + pixel_index;
          errors[entry].smoke_sum += error;
          errors[entry].smoke_max = max(errors[entry].smoke_max, error);
          errors[entry].smoke_count += 1.0;
        }
      }
    }
  }
}
