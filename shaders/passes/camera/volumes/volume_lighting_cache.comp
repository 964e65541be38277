#version 460
// The volume lighting cache (passes/camera/volumes/volume_lighting_cache_pass.h): one thread per
// cell of every volume's box. A cell stores the radiance scattered towards the camera
// per unit sigma_s at its centre: the sum over lights of light_radiance() * phase *
// light_transmittance() (the one shadow lookup every technique answers) in octaves of
// multiple scattering, plus the sky (common/scattered_light.glsl), so smoke
// shadows itself and is shadowed by hair and meshes exactly as in the reference.
// The phase function is evaluated with the direction from the cell to the camera,
// which is the direction of every camera ray through the cell centre; so an
// anisotropic phase stays exact at cell centres (and is interpolated between them).
// Cells that no sample can reach (no non-empty brick within one cell) store 0
// without a lookup.
#extension GL_GOOGLE_include_directive : require

#define AVSM_VOLUME_BINDING_NANOVDB 1
#define AVSM_VOLUME_BINDING_MAJORANTS 2
#define AVSM_VOLUME_BINDING_PARAMETERS 3
#include "common/volume.glsl"
#define AVSM_CACHE_BINDING 4
#include "common/volume_lighting_cache.glsl"
#include "common/lights.glsl"
#define AVSM_SHADOW_BINDING 6
#define AVSM_SHADOW_PAGE_REQUESTS_BINDING 10  // the cells ask for the pages they read
#include "common/shadow_lookup.glsl"

layout(local_size_x = 4, local_size_y = 4, local_size_z = 4) in;

layout(binding = 0, rgba16f) uniform writeonly image3D cache_image;
layout(std430, binding = 5) readonly buffer Lights { GpuLight lights[]; };
#include "common/scattered_light.glsl"

#include "shared/passes/camera/volumes/volume_lighting_cache.h"

// Whether any brick within `reach` (index units per axis) of an index position may hold density.
bool near_density(GpuVolume volume, vec3 index_position, vec3 reach) {
  ivec3 lo = max(volume_brick_of(volume, index_position - reach), ivec3(0));
  ivec3 hi = min(volume_brick_of(volume, index_position + reach), volume.majorant_dims - 1);
  // Constant bounds (lavapipe): a cell reaches at most 3 bricks per axis (cells
  // are never larger than a brick; see VolumeLightingCachePass).
  for (int i = 0; i < 27; ++i) {
    ivec3 b = lo + ivec3(i % 3, (i / 3) % 3, i / 9);
    if (any(greaterThan(b, hi))) continue;
    if (brick_majorant(volume, b) > 0.0) return true;
  }
  return false;
}

void main() {
  ivec3 cell = ivec3(gl_GlobalInvocationID);
  if (any(greaterThanEqual(uvec3(cell), pc.image_size))) return;
  look_up_media_subset(uint(cell.x + cell.y + cell.z));  // the march blends eight cells
  for (uint v = 0u; v < pc.volume_count; ++v) {
    GpuCacheLayout cache = cache_layouts[v];
    ivec3 local = cell - ivec3(0, 0, cache.first_slice);
    if (any(lessThan(local, ivec3(0))) || any(greaterThanEqual(local, cache.dims))) continue;
    vec3 centre = vec3(local) + 0.5;
    vec3 index_position = cache.cell_origin + centre / cache.cells_per_voxel;
    vec3 radiance_sum = vec3(0.0);
    if (near_density(volumes[v], index_position, 1.0 / cache.cells_per_voxel)) {
      vec3 p = (cache.world_from_cell * vec4(centre, 1.0)).xyz;
      radiance_sum = scattered_light(v, index_position, p, normalize(pc.camera_position - p), pc.light_count);
    }
    imageStore(cache_image, cell, vec4(radiance_sum, 1.0));
    return;
  }
  // Outside every volume's box (boxes of different sizes share the image): written
  // too, since a trilinear fetch at a box's edge weighs its neighbour by 0, and
  // 0 times uninitialised memory can be NaN.
  imageStore(cache_image, cell, vec4(0.0));
}
