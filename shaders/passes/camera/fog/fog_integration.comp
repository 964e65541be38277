#version 460
// The fog's integrated grid (passes/camera/fog/fog_integration_pass.h): each froxel column
// walked front to back, froxel k holding the fog from the camera to slice boundary k + 1
// (rgb in-scattered radiance, a transmittance; its layout in shared/fog.h).
#extension GL_GOOGLE_include_directive : require

#define AVSM_FOG_BINDING 2
#include "common/fog.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

layout(binding = 0, rgba16f) uniform readonly image3D scattering_image;
layout(std430, binding = 1) writeonly buffer FogIntegrated { vec4 fog_integrated[]; };

void main() {
  uvec2 column = gl_GlobalInvocationID.xy;
  if (any(greaterThanEqual(column, fog_grid.froxels))) return;
  vec4 fog = vec4(0.0, 0.0, 0.0, 1.0);
  float front = 0.0;
  for (uint k = 0u; k < 256u; ++k) {  // constant bound, break on the count (lavapipe)
    if (k >= fog_grid.slices) break;
    float back = fog_boundary_distance(float(k + 1u));
    vec4 medium = imageLoad(scattering_image, ivec3(column, k));
    fog = fog_then(fog, fog_slice(medium.rgb, medium.a, back - front));
    fog_integrated[(k * fog_grid.froxels.y + column.y) * fog_grid.froxels.x + column.x] = fog;
    front = back;
  }
}
