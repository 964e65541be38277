#version 460
// The fog's froxels (passes/camera/fog/fog_scattering_pass.h): at each froxel's centre, the
// radiance per metre its medium scatters towards the camera from every light (through the
// light's transmittance map, so that smoke, hair and meshes cast shafts) and the sky, and
// its extinction. rgb: radiance per metre; a: sigma_t. (Leaving the froxels behind every
// surface a lookup can reach empty saved 8% of this pass on the default scene under a
// ground fog, as much as the pass finding those surfaces cost: not done.)
#extension GL_GOOGLE_include_directive : require

#define AVSM_SHADOW_BINDING 3
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 7  // the fog asks paged maps for the pages it reads
#include "common/lights.glsl"
#include "common/shadow_lookup.glsl"
layout(std430, binding = 2) readonly buffer Lights { GpuLight lights[]; };
#define AVSM_FOG_BINDING 1
#define AVSM_FOG_LIGHTING
#include "common/fog.glsl"
#include "shared/passes/camera/fog/fog.h"
#include "passes/camera/fog/fog_rays.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, rgba16f) uniform writeonly image3D scattering_image;

void main() {
  uvec3 froxel = gl_GlobalInvocationID;
  if (any(greaterThanEqual(froxel, uvec3(fog_grid.froxels, fog_grid.slices)))) return;
  vec2 pixel = (vec2(froxel.xy) + 0.5) * float(fog_grid.froxel_pixels);
  vec3 direction = fog_ray_direction(pixel);
  float distance = 0.5 * (fog_boundary_distance(float(froxel.z)) + fog_boundary_distance(float(froxel.z + 1u)));
  vec3 p = fog_grid.camera_sky.xyz + distance * direction;
  FogMediumSample medium = fog_medium_at(p);
  look_up_media_subset(froxel.x + froxel.y + froxel.z);  // the integration and the lookups' blend mix neighbours
  vec3 radiance = fog_in_scattering(p, direction, medium, pc.light_count);
  imageStore(scattering_image, ivec3(froxel), vec4(radiance, medium.extinction));
}
