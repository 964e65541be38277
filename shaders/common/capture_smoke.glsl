// Smoke seen from a light (passes/shadows/capture/capture_smoke_pass.h): one thread per light texel
// marches the fog volumes (common/smoke_light_march.glsl) and appends each segment to
// the texel's list. The density comes from the brick atlas where the includer defines
// AVSM_VOLUME_BINDING_ATLAS (capture_smoke.comp), else from NanoVDB
// (capture_smoke_nanovdb.comp: hosts that pass no atlas). Before including, define
// AVSM_CAPTURE_BINDING.
#ifndef AVSM_CAPTURE_SMOKE_GLSL
#define AVSM_CAPTURE_SMOKE_GLSL
#extension GL_GOOGLE_include_directive : require

#define AVSM_VOLUME_BINDING_NANOVDB 0
#define AVSM_VOLUME_BINDING_MAJORANTS 1
#define AVSM_VOLUME_BINDING_PARAMETERS 2
#define AVSM_CAPTURE_APPEND
#include "common/capture_lists.glsl"
#include "shared/passes/shadows/capture/capture_smoke.h"

void smoke_light_segment(ivec2 texel, float entry_depth, float exit_depth, float transmittance) {
  capture_append(texel, pc.list_tile, entry_depth, exit_depth, transmittance);
}
#include "common/smoke_light_march.glsl"

layout(local_size_x = 8, local_size_y = 8) in;

void main() {
  ivec2 texel = ivec2(gl_GlobalInvocationID.xy);
  if (any(greaterThanEqual(uvec2(texel), uvec2(pc.resolution)))) return;
  march_smoke_from_light(texel, pc.raster_origin, pc.raster_resolution, pc.world_from_light, pc.depth_plane, pc.volume_count,
                         pc.volume_mask, pc.samples_per_segment, 3.4e38);
}

#endif
