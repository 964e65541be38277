// The body of the hair lighting passes (passes/camera/hair/hair_lighting_pass.h): one thread per
// strand vertex computes its Kajiya-Kay diffuse lighting with every light's shadow
// lookup, and the fog between the camera and the vertex (the smoke's in-scattering
// and transmittance), which the hair pass interpolates along each ribbon. The 2010
// AVSM sample shaded hair per vertex the same way: a strand's shadow changes little
// along one segment, and a lookup per fragment of a widened ribbon cost far more.
//
// The includer has included a march (common/volume_cached_march.glsl or
// common/volume_reference_march.glsl, which give march_ray, the shadow lookups and
// `lights`) and common/fog.glsl with its integrated grid, then includes this file.
// The fog medium goes in front of the smoke and the fibre together: the vertex's fog is
// the medium's, towards the vertex, over the smoke's (the smoke taken at the vertex).
#ifndef AVSM_HAIR_LIGHTING_GLSL
#define AVSM_HAIR_LIGHTING_GLSL

#extension GL_GOOGLE_include_directive : require
#include "shared/hair.h"
#include "shared/passes/camera/hair/hair_lighting.h"

layout(local_size_x = 64) in;

layout(std430, binding = 0) readonly buffer Points { vec4 points[]; };
layout(std430, binding = 1) readonly buffer Tangents { vec4 tangents[]; };
layout(std430, binding = 2) writeonly buffer VertexLights { HairVertexLight vertex_lights[]; };

#include "common/fibre_light.glsl"

void main() {
  uint i = gl_GlobalInvocationID.x;
  if (i >= pc.point_count) return;
  vec3 p = points[i].xyz;
  // Each ribbon blends two vertices' subsets. (The reference shades hair per fragment,
  // hair_reference.frag, with every virtual light.)
  look_up_media_subset(i);
  vec3 lit = fibre_light(p, tangents[i].xyz, pc.light_count);

  vec3 origin = pc.camera_position.xyz;
  float t_max = length(p - origin);
  MarchState fog = MarchState(1.0, vec3(0.0));
  if (t_max > 0.0 && pc.volume_count > 0u) {
    march_volume_count = pc.volume_count;
    march_light_count = pc.light_count;
#ifdef AVSM_VOLUME_CACHED_MARCH_GLSL
    march_step_voxels = pc.step_voxels;
#endif
    bool touched;
    fog = march_ray(origin, (p - origin) / t_max, t_max, touched);
  }
  vec4 smoke = vec4(fog.in_scattered, fog.transmittance);
  if (fog_grid.enabled != 0u && t_max > 0.0) {
    vec4 clip = pc.view_projection * vec4(p, 1.0);
    vec2 ndc = clip.xy / clip.w;
    vec2 pixel = vec2(0.5 + 0.5 * ndc.x, 0.5 - 0.5 * ndc.y) * vec2(pc.output_size);
    smoke = fog_then(fog_towards(pixel, t_max), smoke);
  }
  vertex_lights[i] = HairVertexLight(vec4(lit, 1.0), smoke);
}

#endif
