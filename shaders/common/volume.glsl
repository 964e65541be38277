// Fog volumes on the GPU: the parameter block, NanoVDB density lookups and the
// majorant grid. (GpuVolume: shared/volume.h.) Shared by every
// pass that marches volumes (the camera march today, the AVSM shadow march later).
//
// Before including, define the bindings of the three storage buffers:
//   AVSM_VOLUME_BINDING_NANOVDB    every volume's NanoVDB grid, one after another
//   AVSM_VOLUME_BINDING_MAJORANTS  every volume's majorant grid and sky visibility, one after another
//   AVSM_VOLUME_BINDING_PARAMETERS one GpuVolume per volume
// optionally, for the density brick atlas (passes/frame/volume_density_atlas.h):
//   AVSM_VOLUME_BINDING_ATLAS      the atlas (sampler3D) at this binding, every
//                                  brick's atlas slot (uint buffer) at +1
// and, to get the brick walk (walk_volume_bricks), AVSM_VOLUME_WALK_STATE: the
// includer's per-ray state type, declared before the include.
#ifndef AVSM_VOLUME_GLSL
#define AVSM_VOLUME_GLSL

#extension GL_GOOGLE_include_directive : require

// PNanoVDB reads its buffer through the global array `pnanovdb_buf_data` (32-bit
// addressing: every grid must lie in the first 4 GiB of the buffer).
layout(std430, binding = AVSM_VOLUME_BINDING_NANOVDB) readonly buffer VolumeNanoVdb { uint pnanovdb_buf_data[]; };
#define PNANOVDB_GLSL
#include "nanovdb/PNanoVDB.h"

layout(std430, binding = AVSM_VOLUME_BINDING_MAJORANTS) readonly buffer VolumeBrickGrids { float volume_brick_grids[]; };

#include "shared/volume.h"

layout(std430, binding = AVSM_VOLUME_BINDING_PARAMETERS) readonly buffer VolumeParameters { GpuVolume volumes[]; };

// ---- NanoVDB density ----

// A cached tree walk for one volume; consecutive samples of a march mostly hit the
// same leaf, so the accessor skips the root-to-leaf descent.
struct DensityReader {
  pnanovdb_buf_t buf;
  pnanovdb_readaccessor_t accessor;
};

DensityReader make_density_reader(GpuVolume volume) {
  DensityReader reader;
  reader.buf.unused = 0u;
  pnanovdb_grid_handle_t grid;
  grid.address.byte_offset = volume.grid_byte_offset;
  pnanovdb_root_handle_t root = pnanovdb_tree_get_root(reader.buf, pnanovdb_grid_get_tree(reader.buf, grid));
  pnanovdb_readaccessor_init(reader.accessor, root);
  return reader;
}

float read_voxel(inout DensityReader reader, ivec3 ijk) {
  pnanovdb_address_t address =
      pnanovdb_readaccessor_get_value_address(PNANOVDB_GRID_TYPE_FLOAT, reader.buf, reader.accessor, ijk);
  return pnanovdb_read_float(reader.buf, address);
}

// Trilinear density at an index-space position, clamped at 0 (negative densities
// absorb nothing). Voxel centres sit at integer coordinates, as in OpenVDB and in the
// CPU reference (nanovdb::SampleFromVoxels<1>). The eight corners are read in a loop
// rather than unrolled: each read inlines NanoVDB's whole cached tree walk, and eight
// copies of it made the shader ~8x larger and slow to compile (seconds on lavapipe).
float sample_density(inout DensityReader reader, vec3 index_position) {
  vec3 base = floor(index_position);
  vec3 w = index_position - base;
  ivec3 i = ivec3(base);
  float density = 0.0;
  for (int corner = 0; corner < 8; ++corner) {
    ivec3 offset = ivec3(corner >> 2, (corner >> 1) & 1, corner & 1);
    vec3 weights = mix(1.0 - w, w, vec3(offset));
    density += weights.x * weights.y * weights.z * read_voxel(reader, i + offset);
  }
  return max(density, 0.0);
}

// ---- Majorants ----

// Upper bound of the density in a brick; 0 means the whole brick is empty.
float brick_majorant(GpuVolume volume, ivec3 brick) {
  ivec3 d = volume.majorant_dims;
  return volume_brick_grids[volume.majorant_offset + uint(brick.x + d.x * (brick.y + d.y * brick.z))];
}

// ---- Sky lighting ----

// scene::sky_lighting at an index-space position, trilinear between the brick corners:
// rgb, the light a uniform sky of radiance 1 scatters there per unit sigma_s over the
// scattering octaves, through the volume itself; a, the chance that light scattered there
// escapes unscattered. A volume without the grid: (0, 0, 0, 1).
vec4 sky_lighting(GpuVolume volume, vec3 index_position) {
  if (volume.sky_offset == kNoSkyLighting) return vec4(0.0, 0.0, 0.0, 1.0);
  ivec3 corners = volume.majorant_dims + 1;
  vec3 c = clamp((index_position - vec3(volume.majorant_origin)) / float(volume.brick_size), vec3(0.0),
                 vec3(volume.majorant_dims));
  ivec3 base = min(ivec3(floor(c)), volume.majorant_dims - 1);
  vec3 w = c - vec3(base);
  vec4 sum = vec4(0.0);
  for (int corner = 0; corner < 8; ++corner) {
    ivec3 offset = ivec3(corner >> 2, (corner >> 1) & 1, corner & 1);
    ivec3 at = base + offset;
    vec3 weights = mix(1.0 - w, w, vec3(offset));
    uint first = volume.sky_offset + 4u * uint(at.x + corners.x * (at.y + corners.y * at.z));
    sum += weights.x * weights.y * weights.z *
           vec4(volume_brick_grids[first], volume_brick_grids[first + 1u], volume_brick_grids[first + 2u],
                volume_brick_grids[first + 3u]);
  }
  return sum;
}

// The brick of the majorant grid that holds an index-space position.
ivec3 volume_brick_of(GpuVolume volume, vec3 index_position) {
  return ivec3(floor((index_position - vec3(volume.majorant_origin)) / float(volume.brick_size)));
}

// ---- Density brick atlas ----
#ifdef AVSM_VOLUME_BINDING_ATLAS
// Each non-empty majorant brick as (brick_size + 1)^3 voxels (the +1 is the trilinear
// reach into the next brick) in one 3D image, sampled with the hardware trilinear
// filter: one texture fetch per sample instead of eight NanoVDB tree walks.
layout(binding = AVSM_VOLUME_BINDING_ATLAS) uniform sampler3D density_atlas;
layout(std430, binding = AVSM_VOLUME_BINDING_ATLAS + 1) readonly buffer VolumeBrickSlots { uint brick_slots[]; };
const uint kEmptyBrickSlot = 0xffffffffu;

// Where one brick's voxels sit in the atlas: atlas texel = index position + offset.
// False for a brick with no slot (it holds no density).
bool atlas_brick_offset(GpuVolume volume, ivec3 brick, out vec3 offset) {
  offset = vec3(0.0);
  if (any(lessThan(brick, ivec3(0))) || any(greaterThanEqual(brick, volume.majorant_dims))) return false;
  ivec3 d = volume.majorant_dims;
  uint slot = brick_slots[volume.majorant_offset + uint(brick.x + d.x * (brick.y + d.y * brick.z))];
  if (slot == kEmptyBrickSlot) return false;
  uint per_layer = uint(volume.atlas_slots.x * volume.atlas_slots.y);
  ivec3 slot_index = ivec3(slot % uint(volume.atlas_slots.x), (slot / uint(volume.atlas_slots.x)) % uint(volume.atlas_slots.y),
                           slot / per_layer);
  ivec3 slot_texel = slot_index * (volume.brick_size + 1) + ivec3(0, 0, volume.atlas_first_slice);
  ivec3 brick_voxel = volume.majorant_origin + brick * volume.brick_size;
  // Voxel centres are at integer index coordinates and texel centres at +0.5.
  offset = vec3(slot_texel - brick_voxel) + 0.5;
  return true;
}

// Trilinear density at an index position inside the brick whose offset is given.
float atlas_density(GpuVolume volume, vec3 index_position, vec3 brick_offset) {
  vec3 texel = index_position + brick_offset;
  return max(volume.atlas_density_scale * textureLod(density_atlas, texel / vec3(textureSize(density_atlas, 0)), 0.0).r,
             0.0);
}
#endif

// ---- Rays ----

// 1 / v with zero components replaced by a huge value of the same sign, so slab
// tests and DDA steps need no special case for axis-parallel rays (and make no NaN).
vec3 safe_reciprocal(vec3 v) {
  const float kTiny = 1e-20;
  return 1.0 / mix(v, mix(vec3(kTiny), vec3(-kTiny), lessThan(v, vec3(0.0))), lessThan(abs(v), vec3(kTiny)));
}

// The part [t_enter, t_exit] of origin + t * direction, t in [t_min, t_max], inside
// the box [box_min, box_max]. False if the ray misses it.
bool clip_ray_to_box(vec3 origin, vec3 direction, vec3 box_min, vec3 box_max, float t_min, float t_max,
                     out float t_enter, out float t_exit) {
  vec3 inverse_direction = safe_reciprocal(direction);
  vec3 t_a = (box_min - origin) * inverse_direction;
  vec3 t_b = (box_max - origin) * inverse_direction;
  vec3 t_near = min(t_a, t_b), t_far = max(t_a, t_b);
  t_enter = max(max(t_near.x, t_near.y), max(t_near.z, t_min));
  t_exit = min(min(t_far.x, t_far.y), min(t_far.z, t_max));
  return t_enter < t_exit;
}

// Where the world ray [t_min, t_max] enters and leaves volume v's support (index-space box).
bool volume_interval_between(uint v, vec3 world_origin, vec3 world_direction, float t_min, float t_max,
                             out float t_enter, out float t_exit) {
  GpuVolume volume = volumes[v];
  vec3 index_origin = (volume.index_from_world * vec4(world_origin, 1.0)).xyz;
  vec3 index_direction = mat3(volume.index_from_world) * world_direction;
  return clip_ray_to_box(index_origin, index_direction, volume.support_min, volume.support_max, t_min, t_max,
                         t_enter, t_exit);
}

bool volume_interval(uint v, vec3 world_origin, vec3 world_direction, float t_max, out float t_enter,
                     out float t_exit) {
  return volume_interval_between(v, world_origin, world_direction, 0.0, t_max, t_enter, t_exit);
}

// The volume hit next after (previous_enter, previous_index) in (entry distance, index)
// order: a selection step instead of a sort, so there is no per-thread array and no
// limit on the volume count (volumes are few).
// Only the stretch [t_min, t_max] of the ray counts.
bool next_volume(uint volume_count, vec3 world_origin, vec3 world_direction, float t_min, float t_max,
                 float previous_enter, int previous_index, out uint next, out float next_enter, out float next_exit) {
  bool found = false;
  next_enter = 3.4e38;
  next = 0u;
  next_exit = 0.0;
  for (uint v = 0u; v < volume_count; ++v) {
    float t_enter, t_exit;
    if (!volume_interval_between(v, world_origin, world_direction, t_min, t_max, t_enter, t_exit)) continue;
    bool after_previous = t_enter > previous_enter || (t_enter == previous_enter && int(v) > previous_index);
    if (after_previous && t_enter < next_enter) {
      found = true;
      next = v;
      next_enter = t_enter;
      next_exit = t_exit;
    }
  }
  return found;
}

// Where the fog composite takes the smoke to be along the ray (common/fog.glsl's
// smoke_over_fogged): the middle of the stretch of [0, t_max] inside the nearest volume.
float smoke_fog_distance(uint volume_count, vec3 world_origin, vec3 world_direction, float t_max) {
  uint v;
  float t_enter, t_exit;
  if (!next_volume(volume_count, world_origin, world_direction, 0.0, t_max, -1.0, -1, v, t_enter, t_exit)) return 0.0;
  return 0.5 * (t_enter + t_exit);
}

// ---- Brick walk ----
#ifdef AVSM_VOLUME_WALK_STATE
// Defined by the includer: called for each stretch [t_start, t_end] of the ray inside
// one brick that may hold density (every brick when skip_empty is false); returns
// false to stop the walk. AVSM_VOLUME_WALK_STATE is the includer's march state.
bool visit_volume_interval(GpuVolume volume, inout DensityReader reader, vec3 world_origin, vec3 world_direction,
                           vec3 index_origin, vec3 index_direction, float t_start, float t_end,
                           inout AVSM_VOLUME_WALK_STATE state);

// Walks volume `v` over [t_enter, t_exit] of the world ray (already clipped to its
// support) brick by brick: a 3D DDA over the majorant grid, in world-ray units t.
void walk_volume_bricks(uint v, vec3 world_origin, vec3 world_direction, float t_enter, float t_exit, bool skip_empty,
                        inout AVSM_VOLUME_WALK_STATE state) {
  GpuVolume volume = volumes[v];
  DensityReader reader = make_density_reader(volume);
  vec3 index_origin = (volume.index_from_world * vec4(world_origin, 1.0)).xyz;
  vec3 index_direction = mat3(volume.index_from_world) * world_direction;
  // Brick space: brick b covers [b, b + 1) on each axis.
  vec3 brick_origin = (index_origin - vec3(volume.majorant_origin)) / float(volume.brick_size);
  vec3 brick_direction = index_direction / float(volume.brick_size);
  vec3 inverse_direction = safe_reciprocal(brick_direction);

  ivec3 brick = clamp(ivec3(floor(brick_origin + t_enter * brick_direction)), ivec3(0), volume.majorant_dims - 1);
  ivec3 brick_step = ivec3(sign(brick_direction));
  // t at which the ray crosses the next brick boundary on each axis, and per brick.
  vec3 next_boundary = vec3(brick) + vec3(greaterThan(brick_direction, vec3(0.0)));
  vec3 t_next = (next_boundary - brick_origin) * inverse_direction;
  vec3 t_delta = abs(inverse_direction);
  // An axis the ray runs parallel to is never crossed.
  bvec3 parallel = equal(brick_step, ivec3(0));
  t_next = mix(t_next, vec3(3.4e38), parallel);

  float t = t_enter;
  // Every step leaves one brick, so the walk ends within the sum of the dimensions
  // (plus slack for a start brick that rounding put one off).
  int max_bricks = volume.majorant_dims.x + volume.majorant_dims.y + volume.majorant_dims.z + 3;
  for (int i = 0; i < max_bricks && t < t_exit; ++i) {
    float t_leave = min(min(t_next.x, t_next.y), t_next.z);
    float t_end = min(t_leave, t_exit);
    if (t_end > t && (!skip_empty || brick_majorant(volume, brick) > 0.0)) {
      if (!visit_volume_interval(volume, reader, world_origin, world_direction, index_origin, index_direction, t, t_end,
                                 state))
        return;
    }
    t = max(t, t_end);
    // Step into the neighbour across the nearest boundary.
    if (t_next.x <= t_next.y && t_next.x <= t_next.z) {
      brick.x += brick_step.x;
      t_next.x += t_delta.x;
    } else if (t_next.y <= t_next.z) {
      brick.y += brick_step.y;
      t_next.y += t_delta.y;
    } else {
      brick.z += brick_step.z;
      t_next.z += t_delta.z;
    }
    if (any(lessThan(brick, ivec3(0))) || any(greaterThanEqual(brick, volume.majorant_dims))) return;
  }
}
#endif

// ---- Scattering ----

// Isotropic phase function: smoke and fog scatter roughly equally in every
// direction at this scale. A Henyey-Greenstein lobe can replace it here without
// touching the marchers: the lighting cache (volume_lighting_cache.comp) evaluates
// it per cell with the cell's own direction to the camera, which is the direction
// of every camera ray through the cell centre.
float phase_function(vec3 to_camera, vec3 to_light) { return 1.0 / (4.0 * 3.14159265358979); }

#endif
