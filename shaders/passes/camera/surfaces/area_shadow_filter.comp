#version 460
// Area lights' soft shadows on opaque surfaces, filtered (passes/camera/surfaces/
// area_shadow_filter_pass.h): each pixel's subset transmittance (opaque.frag's
// out_area_light.a) is averaged over the tile of pixels around it, which between them
// looked up every virtual light, counting only the pixels on its own surface (within
// plane_tolerance of its tangent plane) and weighting each by the area light it reflects;
// then color += its unshadowed area light x that mean.
#extension GL_GOOGLE_include_directive : require
#include "shared/area_shadows.h"
#include "shared/passes/camera/surfaces/area_shadow_filter.h"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba16f) uniform image2D color_image;
layout(binding = 1) uniform sampler2D area_light_texture;
layout(binding = 2) uniform sampler2D depth_texture;
#define DEPTH_SURFACE_TEXTURE depth_texture
#include "common/depth_surface.glsl"

const vec3 kLuminance = vec3(0.2126, 0.7152, 0.0722);

void main() {
  ivec2 pixel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(pixel), pc.output_size))) return;
  vec4 own = texelFetch(area_light_texture, pixel, 0);
  if (dot(own.rgb, kLuminance) <= 0.0) return;  // no area light here that took subsets
  DepthCamera camera = DepthCamera(pc.inverse_view_projection, pc.output_size);
  vec3 p;
  if (!depth_surface_point(camera, pixel, p)) return;
  vec3 n = depth_surface_normal(camera, pixel, p, normalize(pc.camera_position.xyz - p));
  float tolerance = pc.plane_tolerance * distance(p, pc.camera_position.xyz);
  int side = int(pc.tile);
  ivec2 first = pixel - ivec2(side / 2);  // a whole tile: each subset once
  float weights = 0.0, sum = 0.0;
  for (int dy = 0; dy < int(kAreaShadowMaxTile); ++dy) {  // constant bounds (lavapipe)
    if (dy >= side) break;
    for (int dx = 0; dx < int(kAreaShadowMaxTile); ++dx) {
      if (dx >= side) break;
      ivec2 q = first + ivec2(dx, dy);
      vec3 neighbour;
      if (!depth_surface_point(camera, q, neighbour) || abs(dot(neighbour - p, n)) > tolerance) continue;
      vec4 area = texelFetch(area_light_texture, q, 0);
      float weight = dot(area.rgb, kLuminance);
      weights += weight;
      sum += weight * area.a;
    }
  }
  float transmittance = weights > 0.0 ? sum / weights : own.a;
  vec4 color = imageLoad(color_image, pixel);
  imageStore(color_image, pixel, vec4(color.rgb + own.rgb * transmittance, color.a));
}
